#include "integrators/stability/stability_analysis.hpp"

#include <atomic>

#include "integrators/common/linkage_objective.hpp"
#include "integrators/deployment/constrained_newton.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

namespace {

bool has_loads(const LinkageProblem& problem) {
  if (problem.joint_loads().squaredNorm() > 0.0) return true;
  for (const Eigen::VectorXd& f : problem.segment_loads())
    if (f.squaredNorm() > 0.0) return true;
  return false;
}

enum class CheckOutcome { Stable, Unstable, TimeLimit };

// Newton from the problem's state (a copy) under its loads times `factor`,
// saddles kept (held at the average when options.held): Stable when it ends
// at a stable equilibrium without passing an indefinite Hessian.
CheckOutcome solve_scaled(const LinkageProblem& problem, double factor,
                          const StabilityOptions& options,
                          const std::function<void(const StabilityProgress&)>& report) {
  LinkageProblem scaled = problem;
  scaled.scale_loads(factor);
  LinkageObjective objective(scaled);
  NewtonOptions newton = options.unloaded_newton;
  newton.escape.enabled = false;
  std::atomic<bool> stop{false};
  NewtonCallbacks callbacks;
  callbacks.stop = &stop;
  // An iterate with an indefinite Hessian (a shifted step) passed through
  // unstable states: a snap to a remote stable equilibrium past a fold
  // confirms the estimate rather than refuting it.
  bool crossed_unstable = false;
  callbacks.on_iteration = [&](const NewtonReport& r) {
    if (r.iteration > 0) report({"buckling_check", r.iteration, r.energy, r.gradient_measure});
    crossed_unstable = crossed_unstable || r.shifted;
    if (options.deadline.passed()) stop = true;
  };
  SolveResult result;
  if (options.held) {
    ConstrainedNewtonSolver solver(objective, *options.held, newton);
    result = solver.solve(options.held->value(scaled.free_dofs()), callbacks);
  } else {
    result = solve_newton(objective, newton, callbacks);
  }
  if (stop.load()) return CheckOutcome::TimeLimit;
  return result.converged() && result.stable && !crossed_unstable ? CheckOutcome::Stable
                                                                  : CheckOutcome::Unstable;
}

}  // namespace

StabilityAnalysis analyse_stability(LinkageProblem& problem, const StabilityOptions& options) {
  auto report = [&](const StabilityProgress& p) {
    if (options.on_progress) options.on_progress(p);
  };
  StabilityAnalysis out;
  const Eigen::SparseMatrix<double> loaded_hessian = problem.free_hessian();
  // One CHOLMOD solver for H - sigma M and K_0: the same pattern, one
  // symbolic analysis.
  CholeskySolver solver;
  report({"eigen_modes", 0, std::nullopt, std::nullopt});
  EigenModesOptions modes = options.modes;
  modes.deadline = options.deadline;
  out.modes = lowest_eigenmodes(loaded_hessian, problem.free_mass(), modes, &solver);
  out.loaded = has_loads(problem);
  if (!options.buckling || !out.loaded) {
    out.buckling.status = BucklingStatus::NoBuckling;
    return out;
  }
  if (options.deadline.passed()) {
    out.buckling.status = BucklingStatus::TimeLimit;
    return out;
  }
  report({"unloaded_equilibrium", 0, std::nullopt, std::nullopt});
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
  std::atomic<bool> stop{false};
  NewtonCallbacks callbacks;
  callbacks.stop = &stop;
  callbacks.on_iteration = [&](const NewtonReport& r) {
    if (r.iteration > 0)
      report({"unloaded_equilibrium", r.iteration, r.energy, r.gradient_measure});
    if (options.deadline.passed()) stop = true;
  };
  const NewtonResult relaxed = solve_newton(objective, unloaded_newton, callbacks);
  out.unloaded_converged = relaxed.converged();
  out.unloaded_reason = relaxed.reason;
  if (!out.unloaded_converged && stop.load()) {
    out.buckling.status = BucklingStatus::TimeLimit;
    return out;
  }
  if (!out.unloaded_converged || unloaded.num_free() != problem.num_free()) {
    out.buckling.status = BucklingStatus::UnloadedUnstable;
    return out;
  }
  report({"buckling", 0, std::nullopt, std::nullopt});
  BucklingOptions buckling;
  buckling.deadline = options.deadline;
  out.buckling = linearized_buckling(unloaded.free_hessian(), loaded_hessian, buckling, &solver);
  if (out.buckling.status != BucklingStatus::Found || !(options.check_margin > 0.0)) return out;
  report({"buckling_check", 0, std::nullopt, std::nullopt});
  out.check_factor = (1.0 + options.check_margin) * out.buckling.load_factor;
  switch (solve_scaled(problem, *out.check_factor, options, report)) {
    case CheckOutcome::Stable:
      out.stable_at_check = true;
      out.buckling.status = BucklingStatus::Refuted;
      break;
    case CheckOutcome::Unstable:
      break;
    case CheckOutcome::TimeLimit:
      out.buckling.status = BucklingStatus::TimeLimit;
      break;
  }
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
