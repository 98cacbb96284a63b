#include "integrators/stability/stability_analysis.hpp"

#include "integrators/common/linkage_objective.hpp"

namespace xshell {

namespace {

bool has_loads(const LinkageProblem& problem) {
  if (problem.joint_loads().squaredNorm() > 0.0) return true;
  for (const Eigen::VectorXd& f : problem.segment_loads())
    if (f.squaredNorm() > 0.0) return true;
  return false;
}

}  // namespace

StabilityAnalysis analyse_stability(LinkageProblem& problem, const StabilityOptions& options) {
  StabilityAnalysis out;
  const Eigen::SparseMatrix<double> loaded_hessian = problem.free_hessian();
  out.modes = lowest_eigenmodes(loaded_hessian, problem.free_mass(), options.modes);
  out.loaded = has_loads(problem);
  if (!options.buckling || !out.loaded) {
    out.buckling.status = BucklingStatus::NoBuckling;
    return out;
  }
  // The same supports; the default pin is chosen again (the same joint) and
  // holds that joint where it is, as it did in `problem`.
  StaticsSetup unloaded_setup;
  if (problem.default_support_vertex() < 0) unloaded_setup.supports = problem.supports();
  LinkageProblem unloaded(problem.linkage(), unloaded_setup);
  LinkageObjective objective(unloaded);
  // K_0 belongs to the unloaded equilibrium nearest the loaded state: where
  // that is a saddle it stays one (and the buckling is UnloadedUnstable),
  // never replaced by another equilibrium found past it.
  NewtonOptions unloaded_newton = options.unloaded_newton;
  unloaded_newton.escape.enabled = false;
  const NewtonResult relaxed = solve_newton(objective, unloaded_newton);
  out.unloaded_converged = relaxed.converged();
  out.unloaded_reason = relaxed.reason;
  if (!out.unloaded_converged || unloaded.num_free() != problem.num_free()) {
    out.buckling.status = BucklingStatus::UnloadedUnstable;
    return out;
  }
  out.buckling = linearized_buckling(unloaded.free_hessian(), loaded_hessian);
  return out;
}

std::vector<std::vector<Eigen::Vector3d>> node_displacements(const LinkageProblem& problem,
                                                             const Eigen::VectorXd& free_vector) {
  const RodLinkage& l = problem.linkage();
  Eigen::VectorXd reduced = Eigen::VectorXd::Zero(l.num_dofs());
  for (int i = 0; i < problem.num_free(); ++i) reduced[problem.free_indices()[i]] = free_vector[i];
  std::vector<std::vector<Eigen::Vector3d>> out(l.num_segments());
  for (int s = 0; s < l.num_segments(); ++s) {
    const Eigen::VectorXd v = l.full_velocity(s, reduced);
    for (int n = 0; n < l.segment(s).num_nodes(); ++n) out[s].push_back(v.segment<3>(3 * n));
  }
  return out;
}

}  // namespace xshell
