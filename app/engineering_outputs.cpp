#include "engineering_outputs.hpp"

#include <chrono>
#include <cstdio>
#include <future>
#include <optional>

#include "integrators/deployment/average_constraint.hpp"
#include "io/engineering_json.hpp"
#include "io/vtk/engineering_files.hpp"
#include "io/vtk/joints_file.hpp"
#include "vtk_write_options.hpp"

namespace xshell {

namespace {

// The analysis' settings from the configuration's "analysis" and "solver".
StabilityOptions stability_options(const Config& config) {
  StabilityOptions options;
  options.modes.count = config.analysis.modes;
  options.buckling = config.analysis.buckling;
  options.unloaded_newton.gradient_tolerance = config.solver.gradient_tolerance;
  options.unloaded_newton.max_iterations = config.solver.max_iterations;
  if (config.analysis.max_seconds)
    options.deadline.at =
        AnalysisClock::now() + std::chrono::duration_cast<AnalysisClock::duration>(
                                   std::chrono::duration<double>(*config.analysis.max_seconds));
  return options;
}

std::string budget_warning(const Config& config) {
  char text[200];
  std::snprintf(text, sizeof text,
                "the stability analysis stopped at its time budget (analysis.max_seconds = %g s): "
                "what it had not finished is reported \"time_limit\"",
                config.analysis.max_seconds.value_or(0.0));
  return text;
}

std::string refuted_warning(const StabilityAnalysis& stability) {
  char text[320];
  std::snprintf(text, sizeof text,
                "the linearized buckling load factor %.6g was refuted: the structure is still "
                "stable under the loads times %.6g, so no buckling load factor is reported (the "
                "linear estimate fails when the loads move the structure far from its unloaded "
                "equilibrium)",
                stability.buckling.load_factor, stability.check_factor.value_or(0.0));
  return text;
}

}  // namespace

EngineeringSnapshot engineering_results(
    LinkageProblem& problem, const Config& config, const Eigen::Vector3d& origin,
    RunSummary& summary, const std::function<void(const StabilityProgress&)>& on_progress,
    CholeskySolver* factorized) {
  EngineeringResults results;
  results.reactions = support_reactions(problem);
  results.stresses = linkage_stresses(problem.linkage());
  results.joint_forces = joint_forces(problem);

  StabilityOptions options = stability_options(config);
  options.on_progress = on_progress;
  options.factorized = factorized;
  // A deployment by the average angle ends held at it.
  std::optional<AverageConstraint> held;
  if (config.deployment && config.deployment->target == DeploymentTarget::AverageOpeningAngle) {
    held.emplace(average_opening_angle_constraint(problem));
    options.held = &*held;
  }
  const StabilityAnalysis stability = analyse_stability(problem, options);
  if (stability.modes.reason == kTimeLimit ||
      stability.buckling.status == BucklingStatus::TimeLimit)
    summary.warnings.push_back(budget_warning(config));
  if (stability.buckling.status == BucklingStatus::Refuted)
    summary.warnings.push_back(refuted_warning(stability));
  StabilityValues values;
  values.eigen_status = stability.modes.converged ? "converged" : stability.modes.reason;
  for (Eigen::Index k = 0; k < stability.modes.values.size(); ++k)
    values.lowest_eigenvalues.push_back(stability.modes.values[k]);
  values.buckling_status =
      stability.loaded ? buckling_status_name(stability.buckling.status) : "no_loads";
  if (stability.buckling.status == BucklingStatus::Found)
    values.buckling_load_factor = stability.buckling.load_factor;
  results.stability = values;
  summary.engineering = engineering_json(results, origin);

  EngineeringSnapshot snapshot = engineering_snapshot(problem.linkage(), results, origin);
  const bool buckling = stability.buckling.status == BucklingStatus::Found;
  const Eigen::Index count = stability.modes.vectors.cols();
  Eigen::MatrixXd vectors(problem.num_free(), count + (buckling ? 1 : 0));
  vectors.leftCols(count) = stability.modes.vectors;
  if (buckling) vectors.col(count) = stability.buckling.mode;
  auto displacements = node_displacements(problem, vectors);
  for (Eigen::Index k = 0; k < vectors.cols(); ++k)
    snapshot.modes.push_back({k < count ? "mode_" + std::to_string(k) : "buckling_mode",
                              std::move(displacements[static_cast<size_t>(k)])});
  return snapshot;
}

void write_engineering_results(LinkageProblem& problem, const Config& config,
                               const Eigen::Vector3d& origin,
                               const std::filesystem::path& directory, RunSummary& summary) {
  write_engineering_files(engineering_results(problem, config, origin, summary), config, directory);
}

void write_engineering_files(const EngineeringSnapshot& snapshot, const Config& config,
                             const std::filesystem::path& directory) {
  const WriteOptions format = vtk_write_options(config.output);
  // Two at a time: the files are independent, and each one's time is
  // mostly its compression (stresses and modes, the largest, apart).
  std::future<void> other = std::async(std::launch::async, [&] {
    write_reactions_file(snapshot, directory / "reactions.vtp", format);
    write_joints_file(snapshot.joints, directory / "joint_forces.vtp", format);
  });
  write_stresses_file(snapshot, directory / "stresses.vtp", format);
  write_modes_file(snapshot, directory / "modes.vtp", format);
  other.get();
}

}  // namespace xshell
