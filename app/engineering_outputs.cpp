#include "engineering_outputs.hpp"

#include "integrators/stability/stability_analysis.hpp"
#include "io/engineering_json.hpp"
#include "io/vtk/engineering_files.hpp"
#include "io/vtk/joints_file.hpp"

namespace xshell {

EngineeringSnapshot engineering_results(LinkageProblem& problem, const Config& config,
                                        const Eigen::Vector3d& origin, RunSummary& summary) {
  EngineeringResults results;
  results.reactions = support_reactions(problem);
  results.stresses = linkage_stresses(problem.linkage());
  results.joint_forces = joint_forces(problem);

  StabilityOptions options;
  options.unloaded_newton.gradient_tolerance = config.solver.gradient_tolerance;
  options.unloaded_newton.max_iterations = config.solver.max_iterations;
  const StabilityAnalysis stability = analyse_stability(problem, options);
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
  for (Eigen::Index k = 0; k < stability.modes.vectors.cols(); ++k)
    snapshot.modes.push_back(
        {"mode_" + std::to_string(k), node_displacements(problem, stability.modes.vectors.col(k))});
  if (stability.buckling.status == BucklingStatus::Found)
    snapshot.modes.push_back(
        {"buckling_mode", node_displacements(problem, stability.buckling.mode)});
  return snapshot;
}

void write_engineering_results(LinkageProblem& problem, const Config& config,
                               const Eigen::Vector3d& origin,
                               const std::filesystem::path& directory, RunSummary& summary) {
  const EngineeringSnapshot snapshot = engineering_results(problem, config, origin, summary);
  const WriteOptions format{config.output.format == OutputFormat::Ascii ? VtkFormat::Ascii
                                                                        : VtkFormat::Binary};
  write_reactions_file(snapshot, directory / "reactions.vtp", format);
  write_stresses_file(snapshot, directory / "stresses.vtp", format);
  write_joints_file(snapshot.joints, directory / "joint_forces.vtp", format);
  write_modes_file(snapshot, directory / "modes.vtp", format);
}

}  // namespace xshell
