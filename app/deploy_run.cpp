#include "deploy_run.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "deployment_plot.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/deployment.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

namespace xshell {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTable = "deployment.csv";
constexpr const char* kPlot = "deployment.png";
constexpr const char* kHeader =
    "step,average_angle,energy_total,energy_stretching,energy_bending,energy_twisting,torque,"
    "iterations,stable\n";

std::string table_row(const DeploymentStep& s) {
  char text[320];
  std::snprintf(text, sizeof text, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%ld,%s\n", s.step,
                s.average_angle, s.energy.total(), s.energy.stretching, s.energy.bending,
                s.energy.twisting, s.torque, s.iterations, s.stable ? "true" : "false");
  return text;
}

DeploymentOptions deployment_options(const Config& config) {
  const SolverOptions& s = config.solver;
  DeploymentOptions o;
  o.solver =
      s.method == SolverMethod::Dynamics ? DeploymentSolver::Dynamics : DeploymentSolver::Newton;
  o.newton.gradient_tolerance = s.gradient_tolerance;
  o.newton.max_iterations = s.max_iterations;
  o.newton.line_search = s.line_search == LineSearchSetting::Energy
                             ? LineSearch::Energy
                             : LineSearch::KinsolWithEnergyFallback;
  o.dynamics.form = s.first_order ? DynamicsForm::FirstOrder : DynamicsForm::SecondOrder;
  o.dynamics.mass = s.mass == MassSetting::Fictitious ? MassModel::Fictitious : MassModel::Physical;
  o.dynamics.start.velocity =
      s.start == StartSetting::Rest ? DynamicsStart::Rest : DynamicsStart::SlowManifold;
  o.dynamics.damping.coefficient = s.damping.value_or(0.0);
  o.dynamics.stopping.gradient_tolerance = s.gradient_tolerance;
  o.dynamics.stopping.max_steps = s.step_limit();
  return o;
}

const char* status_name(DeploymentStatus s) {
  switch (s) {
    case DeploymentStatus::Completed:
      return "completed";
    case DeploymentStatus::StepFailed:
      return "step_failed";
    case DeploymentStatus::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

}  // namespace

void prepare_deployment(const Config& config, std::optional<LinkageProblem>& problem,
                        StaticsSetup statics) {
  if (!config.deployment) return;
  if (config.joints != JointModel::Rotation)
    throw InputError(config.source +
                     ": deployment: needs \"joints\": \"rotation\" (edge-vector joints have no "
                     "opening-angle unknown to drive)");
  const Deployment& d = *config.deployment;
  if (d.target == DeploymentTarget::AverageOpeningAngle) {
    try {
      (void)average_opening_angle_constraint(*problem);
    } catch (const std::invalid_argument&) {
      throw InputError(
          config.source +
          ": deployment.average_opening_angle: every opening angle is fixed by a support, so the "
          "average cannot be driven");
    }
    return;
  }
  const std::vector<int> valence = valences(problem->linkage().graph());
  if (problem->default_support_vertex() >= 0)
    statics.supports.push_back(
        {problem->default_support_vertex(), {SupportDof::Position, SupportDof::Orientation}});
  for (size_t i = 0; i < d.joint_angles.size(); ++i) {
    const int v = d.joint_angles[i].vertex;
    if (valence[v] < 2)
      throw InputError(config.source + ": deployment.joint_angles[" + std::to_string(i) +
                       "].vertex: vertex " + std::to_string(v) +
                       " is a free rod end, which has no opening angle");
    statics.supports.push_back({v, {SupportDof::OpeningAngle}});
  }
  RodLinkage linkage = problem->linkage();
  problem.emplace(std::move(linkage), statics);
}

DeploymentRun run_deployment(const Config& config, LinkageProblem& problem, const fs::path& dir,
                             const DeploymentHooks& hooks, RunSummary& summary) {
  const Deployment& d = *config.deployment;
  DeploymentPlan plan;
  plan.steps = d.steps;
  if (d.target == DeploymentTarget::AverageOpeningAngle) {
    plan.average_angle = d.average_opening_angle;
  } else {
    for (const JointAngle& a : d.joint_angles)
      plan.joint_angles.push_back(
          {problem.linkage().topology().joint_of_vertex[a.vertex], a.angle});
  }
  const DeploymentOptions options = deployment_options(config);

  DeploymentRun run;
  std::atomic<bool> stop{false};
  auto poll = [&] {
    if ((hooks.halted && hooks.halted()) || !run.output_error.empty()) stop = true;
  };
  std::string table = kHeader;
  int solving = 0;      // the step being solved
  long iterations = 0;  // over all steps, for the history
  DeploymentCallbacks callbacks;
  callbacks.stop = &stop;
  callbacks.on_newton_iteration = [&](const NewtonReport& r) {
    if (r.iteration > 0) ++iterations;
    summary.history.push_back(
        {iterations, double(solving), r.energy, r.gradient_measure, r.step_norm, 0.0, r.seconds});
    if (hooks.progress && r.iteration > 0)
      std::fprintf(
          stderr,
          "  newton %3d  energy %.10e  gradient %.3e  step %.3e  factorizations %ld%s  %.3f s\n",
          r.iteration, r.energy, r.gradient_measure, r.step_norm, r.factorizations,
          r.shifted ? " (shifted)" : "", r.seconds);
    poll();
  };
  callbacks.on_dynamics_step = [&](const DynamicsReport& r) {
    if (r.step > 0) ++iterations;
    summary.history.push_back({iterations, double(solving), r.energy, r.gradient_measure,
                               r.step_size, r.kinetic_energy, 0.0});
    if (hooks.progress && r.step > 0 && r.step % 100 == 0)
      std::fprintf(stderr,
                   "  dynamics %6ld  t %.4e  dt %.3e  energy %.10e  kinetic %.3e  gradient %.3e\n",
                   r.step, r.time, r.step_size, r.energy, r.kinetic_energy, r.gradient_measure);
    poll();
  };
  callbacks.on_step = [&](const DeploymentStep& s) {
    solving = s.step + 1;
    table += table_row(s);
    try {
      write_file_atomically(dir / kTable, table);
    } catch (const std::exception& e) {
      if (run.output_error.empty()) run.output_error = e.what();
    }
    if (hooks.snapshot) hooks.snapshot(s.step, false);
    if (hooks.progress)
      std::fprintf(stderr,
                   "deploy step %3d  s %.4f  angle %.6f rad (%.3f deg)  energy %.6e  torque %.6e  "
                   "iterations %ld%s%s  "
                   "%.2f s\n",
                   s.step, s.fraction, s.average_angle, s.average_angle * 180.0 / M_PI,
                   s.energy.total(), s.torque, s.iterations, s.stable ? "" : "  NOT stable",
                   s.halvings > 0 ? "  (halved)" : "", s.seconds);
    poll();
  };
  poll();
  const DeploymentResult result = deploy(problem, plan, options, callbacks);
  const int last = result.steps.empty() ? 0 : result.steps.back().step;
  if (hooks.snapshot) hooks.snapshot(last, true);

  const bool completed = result.completed();
  run.interrupted = result.status == DeploymentStatus::Interrupted && run.output_error.empty();
  summary.status = completed ? "converged" : run.interrupted ? "interrupted" : "step_failed";
  summary.reason = "deployment " + std::string(to_string(result.status)) + ": " + result.reason;
  summary.converged = completed;
  summary.iterations = result.iterations;
  if (!result.steps.empty()) {
    summary.stable = result.steps.back().stable;
    summary.gradient_norm = result.steps.back().gradient_measure;
  } else {
    summary.gradient_norm = problem.gradient_measure();  // the start, never in equilibrium
  }
  DeploymentSummary ds;
  ds.actuation =
      d.target == DeploymentTarget::AverageOpeningAngle ? "average_opening_angle" : "joint_angles";
  ds.status = status_name(result.status);
  ds.steps = last;
  ds.failed_attempts = result.failed_attempts;
  ds.iterations = result.iterations;
  ds.start_average_angle = result.start_angle;
  if (d.target == DeploymentTarget::AverageOpeningAngle)
    ds.target_average_angle = d.average_opening_angle;
  ds.final_average_angle = average_opening_angle(problem.linkage());
  ds.final_torque = result.steps.empty() ? 0.0 : result.steps.back().torque;

  std::error_code ignored;
  fs::remove(dir / kPlot, ignored);  // never leave an earlier run's plot behind
  if (!result.steps.empty() && run.output_error.empty()) {
    const PlotOutcome plot = plot_deployment(dir / kTable, dir / kPlot);
    if (plot.written)
      ds.plot = kPlot;
    else
      std::cerr << "xshell: " << kPlot << " skipped: " << plot.message << "\n";
  }
  std::fprintf(
      stderr,
      "xshell: deployment %s: %d steps (%d retried), average opening angle %.6f rad (%.3f deg), "
      "torque %.6e, %ld iterations, %.2f s\n",
      ds.status.c_str(), ds.steps, ds.failed_attempts, ds.final_average_angle,
      ds.final_average_angle * 180.0 / M_PI, ds.final_torque, ds.iterations, result.seconds);
  summary.deployment = ds;
  return run;
}

}  // namespace xshell
