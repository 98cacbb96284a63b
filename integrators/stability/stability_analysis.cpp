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

// One Newton solve of the analysis (stage `stage`), from the problem's
// state, saddles kept (the unloaded equilibrium nearest the loaded state,
// or the check's), held at the average when `held`; stopped at the
// deadline.
struct StageSolve {
  SolveResult result;
  bool stopped = false;  // by the deadline
  bool shifted = false;  // some iterate's Hessian was indefinite
};

// Lends `solver` to a NewtonSolver for the length of a solve (its analysis
// and last factorization reused, not copied), and takes it back, with the
// final state's factorization, however the solve ends.
class LentCholesky {
 public:
  LentCholesky(NewtonSolver& newton, CholeskySolver& solver) : newton_(newton), solver_(solver) {
    newton_.swap_cholesky(solver_);
  }
  ~LentCholesky() { newton_.swap_cholesky(solver_); }
  LentCholesky(const LentCholesky&) = delete;
  LentCholesky& operator=(const LentCholesky&) = delete;

 private:
  NewtonSolver& newton_;
  CholeskySolver& solver_;
};

StageSolve solve_in_stage(LinkageProblem& problem, const char* stage, const AverageConstraint* held,
                          const StabilityOptions& options, CholeskySolver& analysed,
                          const std::function<void(const StabilityProgress&)>& report) {
  LinkageObjective objective(problem);
  NewtonOptions newton = options.unloaded_newton;
  newton.escape.enabled = false;
  newton.grow_step_cap = true;  // a linkage springing back from its removed loads
  // Held solves keep the line: along the linkage's curve scary_face's
  // analysis under steel-density gravity took 2.8 s instead of 2.0.
  if (held) newton.follow_path = false;
  std::atomic<bool> stop{false};
  NewtonCallbacks callbacks;
  callbacks.stop = &stop;
  StageSolve out;
  callbacks.on_iteration = [&](const NewtonReport& r) {
    if (r.iteration > 0) report({stage, r.iteration, r.energy, r.gradient_measure});
    out.shifted = out.shifted || r.shifted;
    if (options.deadline.passed()) stop = true;
  };
  if (held) {
    ConstrainedNewtonSolver solver(objective, *held, newton);
    out.result = solver.solve(held->value(problem.free_dofs()), callbacks);
  } else {
    NewtonSolver solver(objective, newton);
    const LentCholesky lent(solver, analysed);
    out.result = solver.solve(callbacks);
  }
  out.stopped = stop.load();
  return out;
}

// The check of a found estimate (the header): under the loads times
// out.check_factor, a stable equilibrium reached without an indefinite
// Hessian on the way refutes it (a snap past a fold to a remote stable
// state passes through unstable ones, and confirms it). `scaled`: a copy
// of `problem` made earlier (the unloaded one), assigned the loaded state
// again: its memory is reused, where a new copy's fresh pages cost up to
// 15 ms on manta_ray (the check's median under steel-density gravity went
// from 36 to 29 ms).
void check_estimate(const LinkageProblem& problem, LinkageProblem& scaled,
                    const StabilityOptions& options, CholeskySolver& analysed,
                    const std::function<void(const StabilityProgress&)>& report,
                    StabilityAnalysis& out) {
  report({"buckling_check", 0, std::nullopt, std::nullopt});
  out.check_factor = (1.0 + options.check_margin) * out.buckling.load_factor;
  scaled = problem;
  scaled.scale_loads(*out.check_factor);
  const StageSolve check =
      solve_in_stage(scaled, "buckling_check", options.held, options, analysed, report);
  if (check.stopped) {
    out.buckling.status = BucklingStatus::TimeLimit;
    return;
  }
  out.stable_at_check = check.result.converged() && check.result.stable && !check.shifted;
  if (out.stable_at_check) out.buckling.status = BucklingStatus::Refuted;
}

// The linearized buckling of K_0 and K_L, on the constraint's null space
// (B^T K B, the mode carried back by B) when the state is held: there the
// actuation removes the opening mode, which the loads would otherwise
// soften first.
BucklingResult held_buckling(const Eigen::SparseMatrix<double>& K0,
                             const Eigen::SparseMatrix<double>& KL, bool K0_definite,
                             const StabilityOptions& options, CholeskySolver& solver) {
  BucklingOptions buckling;
  buckling.deadline = options.deadline;
  buckling.unloaded_positive_definite = K0_definite;
  if (!options.held) return linearized_buckling(K0, KL, buckling, &solver);
  const AverageConstraint& held = *options.held;
  BucklingResult out = linearized_buckling(held.reduce(K0), held.reduce(KL), buckling, &solver);
  if (out.status == BucklingStatus::Found) out.mode = held.expand(out.mode);
  return out;
}

}  // namespace

StabilityAnalysis analyse_stability(LinkageProblem& problem, const StabilityOptions& options) {
  auto report = [&](const StabilityProgress& p) {
    if (options.on_progress) options.on_progress(p);
  };
  StabilityAnalysis out;
  const Eigen::SparseMatrix<double> loaded_hessian = problem.free_hessian();
  // One CHOLMOD solver for H - sigma M, the stages' Newton solves and K_0:
  // the same pattern, one symbolic analysis (a held state's reduced B^T K B
  // has its own). The caller's, when it has H factorized already.
  CholeskySolver own;
  CholeskySolver& solver = options.factorized ? *options.factorized : own;
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
  // The same supports (the same free unknowns), the loads scaled to none: a
  // copy keeps the assembly's pattern, which a new problem would build
  // again (30 ms on manta_ray, 6 Newton iterations' worth).
  LinkageProblem unloaded = problem;
  unloaded.scale_loads(0.0);
  // K_0 belongs to the unloaded equilibrium nearest the loaded state: where
  // that is a saddle it stays one (and the buckling is UnloadedUnstable),
  // never replaced by another equilibrium found past it. A held state
  // stays held: the actuation that keeps a deployed linkage open does so
  // with and without the loads.
  const StageSolve solved =
      solve_in_stage(unloaded, "unloaded_equilibrium", options.held, options, solver, report);
  const SolveResult& relaxed = solved.result;
  out.unloaded_converged = relaxed.converged();
  out.unloaded_reason = relaxed.reason;
  if (!out.unloaded_converged && solved.stopped) {
    out.buckling.status = BucklingStatus::TimeLimit;
    return out;
  }
  if (!out.unloaded_converged) {
    out.buckling.status = BucklingStatus::UnloadedUnstable;
    return out;
  }
  report({"buckling", 0, std::nullopt, std::nullopt});
  // Newton's stability test there factorized K_0 (B^T K_0 B when held):
  // relaxed.stable says whether it is definite.
  out.buckling =
      held_buckling(unloaded.free_hessian(), loaded_hessian, relaxed.stable, options, solver);
  if (out.buckling.status == BucklingStatus::Found && options.check_margin > 0.0)
    check_estimate(problem, unloaded, options, solver, report, out);
  return out;
}

std::vector<std::vector<std::vector<Eigen::Vector3d>>> node_displacements(
    const LinkageProblem& problem, const Eigen::MatrixXd& free_vectors) {
  const RodLinkage& l = problem.linkage();
  const Eigen::Index count = free_vectors.cols();
  Eigen::MatrixXd reduced = Eigen::MatrixXd::Zero(l.num_dofs(), count);
  for (int i = 0; i < problem.num_free(); ++i)
    reduced.row(problem.free_indices()[i]) = free_vectors.row(i);
  std::vector<std::vector<std::vector<Eigen::Vector3d>>> out(
      static_cast<size_t>(count), std::vector<std::vector<Eigen::Vector3d>>(l.num_segments()));
  for (int s = 0; s < l.num_segments(); ++s) {
    const Eigen::MatrixXd v = l.full_velocities(s, reduced);
    for (Eigen::Index c = 0; c < count; ++c)
      for (int n = 0; n < l.segment(s).num_nodes(); ++n)
        out[static_cast<size_t>(c)][s].push_back(v.col(c).segment<3>(3 * n));
  }
  return out;
}

std::vector<std::vector<Eigen::Vector3d>> node_displacements(const LinkageProblem& problem,
                                                             const Eigen::VectorXd& free_vector) {
  return node_displacements(problem, Eigen::MatrixXd(free_vector)).front();
}

}  // namespace xshell
