#include "deploy_run.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "deployment_plot.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/deployment.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "scoped_seconds.hpp"

namespace xshell {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTable = "deployment.csv";
constexpr const char* kPlot = "deployment.png";
// A deployment whose every step converged (SolveStatus::Converged) is
// "completed" in its summary object and its reason.
constexpr const char* kCompleted = "completed";
constexpr const char* kHeader =
    "step,average_angle,energy_total,energy_stretching,energy_bending,energy_twisting,torque,"
    "iterations,stable,min_opening_angle,max_opening_angle,factorizations\n";

std::string table_row(const DeploymentStep& s) {
  char text[400];
  std::snprintf(text, sizeof text,
                "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%ld,%s,%.17g,%.17g,%ld\n", s.step,
                s.average_angle, s.energy.total(), s.energy.stretching, s.energy.bending,
                s.energy.twisting, s.torque, s.iterations, s.stable ? "true" : "false",
                s.min_opening_angle, s.max_opening_angle, s.factorizations);
  return text;
}

DeploymentOptions deployment_options(const Config& config) {
  DeploymentOptions o;
  o.solver = config.solver.method == SolverMethod::Dynamics ? DeploymentSolver::Dynamics
                                                            : DeploymentSolver::Newton;
  o.newton = newton_options(config.solver);
  o.dynamics = dynamics_options(config.solver);
  o.buckling_direction = config.solver.buckling_direction;
  return o;
}

DeploymentPlan make_plan(const Deployment& d, const LinkageProblem& problem) {
  DeploymentPlan plan;
  plan.steps = d.steps;
  plan.largest_step = d.largest_step;
  if (d.target == DeploymentTarget::AverageOpeningAngle) {
    plan.average_angle = d.average_opening_angle;
  } else {
    for (const JointAngle& a : d.joint_angles)
      plan.joint_angles.push_back(
          {problem.linkage().topology().joint_of_vertex[a.vertex], a.angle});
  }
  return plan;
}

// The deployment's callbacks: every solver iteration into the history
// (numbered over all steps, at the time of the step being solved) and a
// progress line; every accepted step into deployment.csv (rewritten
// atomically), a VTK step and a progress line. Stops the deployment on the
// run's stop flag and on its own output failure.
class DeploymentRecorder {
 public:
  DeploymentRecorder(const fs::path& dir, const RunHooks& hooks) : dir_(dir), hooks_(hooks) {}

  DeploymentCallbacks callbacks() {
    DeploymentCallbacks c;
    c.stop = &stop_;
    c.on_newton_iteration = [this](const NewtonReport& r) { on_report(r, true); };
    // Thousands of time steps: a progress line every 100.
    c.on_dynamics_step = [this](const DynamicsReport& r) { on_report(r, r.step % 100 == 0); };
    c.on_step = [this](const DeploymentStep& s) { on_step(s); };
    return c;
  }

  void poll() {
    hooks_.poll();
    if (hooks_.stop->load() || !output_error_.empty()) stop_ = true;
  }

  const std::string& output_error() const { return output_error_; }

 private:
  // A solver's report (the step's start is reported again by each solve).
  template <class Report>
  void on_report(const Report& r, bool print) {
    if (report_number(r) > 0) ++iterations_;
    hooks_.history->push_back(history_record(r, iterations_, solving_));
    if (hooks_.progress->every_iteration() && report_number(r) > 0 && print)
      print_progress(r, true);
    ProgressSample sample = progress_sample(r, "deploy");
    sample.step = solving_;  // the step being solved (its angle: on_step's sample)
    hooks_.progress->sample(sample);
    poll();
  }

  void on_step(const DeploymentStep& s) {
    solving_ = s.step + 1;
    table_ += table_row(s);
    {
      const ScopedSeconds timer(hooks_.output_seconds);
      try {
        if (!dir_.empty()) write_file_atomically(dir_ / kTable, table_);
      } catch (const std::exception& e) {
        if (output_error_.empty()) output_error_ = e.what();
      }
    }
    // The series' time is the average opening angle (README, "Outputs");
    // the start is always written.
    hooks_.snapshot(s.average_angle, s.step == 0);
    hooks_.progress->sample(
        {"deploy", "step", s.step, s.energy.total(), std::nullopt, s.step, s.average_angle});
    warn_outside_opening_range(s);
    if (hooks_.progress->every_iteration())
      std::fprintf(stderr,
                   "deploy step %3d  s %.4f  angle %.6f rad (%.3f deg)  energy %.6e  torque %.6e  "
                   "iterations %ld%s%s  "
                   "%.2f s\n",
                   s.step, s.fraction, s.average_angle, s.average_angle * 180.0 / M_PI,
                   s.energy.total(), s.torque, s.iterations, s.stable ? "" : "  NOT stable",
                   s.halvings > 0 ? "  (halved)" : "", s.seconds);
    poll();
  }

  // Once per deployment, at the first step that takes a joint out of (0,
  // pi); the final state's joints are listed by the run's own warning.
  void warn_outside_opening_range(const DeploymentStep& s) {
    if (s.outside_opening_range == 0 || warned_outside_) return;
    warned_outside_ = true;
    char text[200];
    std::snprintf(text, sizeof text,
                  "deployment step %d: %d joint%s outside (0, pi) (smallest opening angle %.6g "
                  "rad): rods pass through each other there",
                  s.step, s.outside_opening_range, s.outside_opening_range == 1 ? "" : "s",
                  s.min_opening_angle);
    hooks_.warn(text);
  }

  fs::path dir_;
  const RunHooks& hooks_;
  bool warned_outside_ = false;
  std::atomic<bool> stop_{false};
  std::string table_ = kHeader;
  int solving_ = 0;      // the step being solved
  long iterations_ = 0;  // over all steps, for the history
  std::string output_error_;
};

// The summary's "deployment" object.
DeploymentSummary deployment_summary(const Deployment& d, const DeploymentResult& result,
                                     const LinkageProblem& problem) {
  DeploymentSummary ds;
  ds.actuation =
      d.target == DeploymentTarget::AverageOpeningAngle ? "average_opening_angle" : "joint_angles";
  ds.status = result.converged() ? kCompleted : to_string(result.status);
  ds.steps = result.steps.empty() ? 0 : result.steps.back().step;
  ds.failed_attempts = result.failed_attempts;
  ds.curvature_dropped = result.curvature_dropped;
  ds.round_off_floor_steps = result.round_off_floor_steps;
  ds.iterations = result.iterations;
  ds.factorizations = result.factorizations;
  ds.chord_corrections = result.chord_corrections;
  ds.start_average_angle = result.start_angle;
  if (d.target == DeploymentTarget::AverageOpeningAngle)
    ds.target_average_angle = d.average_opening_angle;
  ds.final_average_angle = average_opening_angle(problem.linkage());
  ds.final_torque = result.steps.empty() ? 0.0 : result.steps.back().torque;
  if (result.branch_switch_step >= 0) ds.branch_switch_step = result.branch_switch_step;
  return ds;
}

// The plot's child, started before the deployment (deployment_plot.hpp);
// none for a run that writes no files. An earlier run's plot is removed at
// once, so that none is ever left behind.
std::unique_ptr<DeploymentPlotter> start_plot(const fs::path& dir, const UnitNames& units) {
  if (dir.empty()) return nullptr;
  std::error_code ignored;
  fs::remove(dir / kPlot, ignored);
  return std::make_unique<DeploymentPlotter>(dir / kTable, dir / kPlot, units);
}

// Has the plotter draw (when there is a table) and returns the wait for it,
// which names the plot in the summary or says why there is none.
std::function<void(DeploymentSummary&)> draw_plot(std::unique_ptr<DeploymentPlotter> plotter,
                                                  bool has_table, bool messages) {
  if (!plotter) return {};
  plotter->start(has_table);
  std::shared_ptr<DeploymentPlotter> shared = std::move(plotter);
  return [shared, has_table, messages](DeploymentSummary& ds) {
    const PlotOutcome plot = shared->finish(has_table);
    if (plot.written)
      ds.plot = kPlot;
    else if (has_table && messages)
      std::cerr << "xshell: " << kPlot << " skipped: " << plot.message << "\n";
  };
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
  // The default pin, given explicitly: held where it is (a given support
  // holds input + displacement, statics_problem.hpp).
  if (const int pin = problem->default_support_vertex(); pin >= 0)
    statics.supports.push_back(
        {pin,
         {SupportDof::Position, SupportDof::Orientation},
         problem->vertex_positions()[pin] - problem->linkage().graph().vertices[pin]});
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

SolverRun run_deployment(const Config& config, LinkageProblem& problem, const fs::path& dir,
                         const RunHooks& hooks) {
  const Deployment& d = *config.deployment;
  DeploymentRecorder recorder(dir, hooks);
  std::unique_ptr<DeploymentPlotter> plotter = start_plot(dir, config.units);
  recorder.poll();
  const DeploymentResult result =
      deploy(problem, make_plan(d, problem), deployment_options(config), recorder.callbacks());
  hooks.snapshot(average_opening_angle(problem.linkage()), true);

  SolverRun run;
  run.output_error = recorder.output_error();
  run.result = result;
  run.result.reason = std::string("deployment ") +
                      (result.converged() ? kCompleted : describe(result.status)) + ": " +
                      result.reason;
  // Stopped by its own output failure, not by a signal or the run's outputs.
  if (result.status == SolveStatus::Interrupted && !run.output_error.empty())
    run.result.status = SolveStatus::StepFailed;
  DeploymentSummary ds = deployment_summary(d, result, problem);
  run.finish_plot = draw_plot(std::move(plotter), !result.steps.empty() && run.output_error.empty(),
                              hooks.messages);
  if (hooks.messages)
    std::fprintf(
        stderr,
        "xshell: deployment %s: %d steps (%d retried), average opening angle %.6f rad (%.3f deg), "
        "torque %.6e, %ld iterations, %.2f s\n",
        ds.status.c_str(), ds.steps, ds.failed_attempts, ds.final_average_angle,
        ds.final_average_angle * 180.0 / M_PI, ds.final_torque, ds.iterations, result.seconds);
  run.deployment = ds;
  return run;
}

}  // namespace xshell
