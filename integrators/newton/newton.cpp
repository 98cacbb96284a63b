#include "integrators/newton/newton.hpp"

#include <kinsol/kinsol.h>
#include <kinsol/kinsol_ls.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/linear_algebra/sundials_handles.hpp"
#include "integrators/newton/chord_correction.hpp"
#include "integrators/newton/descent_step.hpp"
#include "integrators/newton/iteration_checks.hpp"
#include "integrators/newton/kinsol_system.hpp"

namespace xshell {

namespace {

// Smallest function scale passed to KINSOL, which requires positive scales;
// an unknown of weight 0 is then (practically) ignored, as in our measure.
constexpr double kMinimumScale = 1e-300;

// The state of one solve() between its steps.
struct NewtonRun {
  explicit NewtonRun(const NewtonCallbacks& callbacks) : callbacks(callbacks) {}
  const NewtonCallbacks& callbacks;
  NewtonResult result;
  NewtonReport report;               // of the last iteration (or the start)
  bool stagnant = false;             // the last step was below the scaled step tolerance
  long factorizations_at_start = 0;  // of the solver's CHOLMOD counter
  // Iterations done when the last saddle was left: the iteration limit
  // counts from there (the descent from a saddle is a solve of its own).
  long iterations_at_escape = 0;
  // The cap on the energy line search's step: NewtonOptions::max_step, or
  // with grow_step_cap grown_step_cap's (descent_step.hpp).
  double step_cap = 0.0;
};

}  // namespace

struct NewtonSolver::Impl {
  Objective& objective;
  const NewtonOptions& options;
  // Declaration order = construction order; SUNDIALS objects after the context.
  SunContext context;
  ObjectiveEvaluator evaluator;
  NewtonSystem system;
  NVector u, u_scale, f_scale;
  SunMatrix placeholder;
  SunLinearSolver linear_solver;
  KinsolMemory kinsol;
  std::string last_message;

  Impl(Objective& objective, const NewtonOptions& options)
      : objective(objective),
        options(options),
        evaluator(objective),
        system(evaluator, options.shift) {
    const Eigen::Index n = objective.size();
    u = make_serial_vector(n, context);
    u_scale = make_serial_vector(n, context);
    f_scale = make_serial_vector(n, context);
    N_VConst(1.0, u_scale.get());
    N_VConst(1.0, f_scale.get());
    placeholder = make_placeholder_matrix(context);
    linear_solver = make_direct_linear_solver(context, system);
    kinsol.reset(KINCreate(context));
    if (!kinsol) throw std::bad_alloc();
    void* k = kinsol.get();
    check_sundials(KINInit(k, &NewtonSystem::residual, u.get()), "KINInit");
    check_sundials(KINSetUserData(k, &system), "KINSetUserData");
    check_sundials(KINSetErrHandlerFn(k, keep_sundials_message, &last_message),
                   "KINSetErrHandlerFn");
    check_sundials(KINSetLinearSolver(k, linear_solver.get(), placeholder.get()),
                   "KINSetLinearSolver");
    check_sundials(KINSetJacFn(k, &NewtonSystem::jacobian), "KINSetJacFn");
    check_sundials(KINSetNumMaxIters(k, 1), "KINSetNumMaxIters");
    check_sundials(KINSetMaxSetupCalls(k, 1), "KINSetMaxSetupCalls");
    check_sundials(KINSetNoResMon(k, SUNTRUE), "KINSetNoResMon");
    check_sundials(KINSetFuncNormTol(k, options.gradient_tolerance), "KINSetFuncNormTol");
    check_sundials(KINSetScaledStepTol(k, options.scaled_step_tolerance), "KINSetScaledStepTol");
    check_sundials(KINSetMaxNewtonStep(k, options.max_step), "KINSetMaxNewtonStep");
  }

  long factorizations() { return system.cholesky().stats().factorizations; }
  void start(NewtonRun& run);
  bool finished(int iteration, NewtonRun& run);
  bool iterate(int iteration, NewtonRun& run);
  int kinsol_step(const Eigen::VectorXd& q0);
  bool energy_step(const Eigen::VectorXd& q0, const Eigen::VectorXd& weights, NewtonRun& run,
                   double& energy);
  void correct_by_chords(const Eigen::VectorXd& weights, NewtonRun& run, double& energy);
  bool accept_step(int iteration, const Eigen::VectorXd& q0, double energy, NewtonRun& run);
  void restore(const Eigen::VectorXd& q0);
  void rethrow_if_fatal(const Eigen::VectorXd& q0);
  void finish(NewtonRun& run);
  bool escape(int& iteration, NewtonRun& run);
};

NewtonSolver::NewtonSolver(Objective& objective, NewtonOptions options)
    : objective_(objective), options_(options) {
  if (objective.size() > 0) impl_ = std::make_unique<Impl>(objective, options_);
}

NewtonSolver::~NewtonSolver() = default;

void NewtonSolver::swap_cholesky(CholeskySolver& other) {
  if (impl_) std::swap(impl_->system.cholesky(), other);
}

CholeskyStats NewtonSolver::cholesky_stats() const {
  return impl_ ? impl_->system.cholesky().stats() : CholeskyStats{};
}

namespace {

// Maps a failed KINSol flag (not SUCCESS / MAXITER_REACHED) to a result.
void classify_failure(int flag, const ObjectiveEvaluator& evaluator, const NewtonSystem& system,
                      const std::string& message, NewtonResult& result) {
  const bool nonfinite = evaluator.last_failure() == EvaluationFailure::NonFinite;
  const std::string detail = evaluator.last_message().empty() ? message : evaluator.last_message();
  switch (flag) {
    case KIN_LSETUP_FAIL:
    case KIN_LSOLVE_FAIL:
    case KIN_LINSOLV_NO_RECOVERY:
      if (nonfinite) {
        result.status = SolveStatus::NonFinite;
        result.reason = "linear solver setup: " + detail;
      } else {
        result.status = SolveStatus::LinearSolverFailed;
        result.reason = system.setup_failed()
                            ? "the Hessian could not be factorized even with the largest shift"
                            : "linear solver failed: " + message;
      }
      return;
    case KIN_SYSFUNC_FAIL:
    case KIN_FIRST_SYSFUNC_ERR:
    case KIN_REPTD_SYSFUNC_ERR:
      result.status = nonfinite ? SolveStatus::NonFinite : SolveStatus::LineSearchFailed;
      result.reason = "the objective failed at every trial point: " + detail;
      return;
    case KIN_LINESEARCH_NONCONV:
    case KIN_LINESEARCH_BCFAIL:
    case KIN_STEP_LT_STPTOL:
    case KIN_MXNEWT_5X_EXCEEDED:
      result.status = SolveStatus::LineSearchFailed;
      result.reason = "KINSOL: " + kinsol_flag_name(flag) +
                      (system.any_shift() ? " after a shifted (indefinite Hessian) step" : "");
      return;
    default:
      throw std::runtime_error("KINSol failed: " + kinsol_flag_name(flag) + ": " + message);
  }
}

}  // namespace

NewtonResult NewtonSolver::solve(const NewtonCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  NewtonRun run(callbacks);
  run.step_cap = options_.max_step;
  if (!impl_) {  // no unknowns: trivially in equilibrium
    set_no_unknowns(objective_.energy(), run.result);
    return run.result;
  }
  const ExactHessianAtExit exact_at_exit(objective_);
  impl_->start(run);
  run.result.setup_seconds = seconds_since(start);
  int iteration = 0;
  do {  // iterations, and again after each escape from a saddle
    for (; !impl_->finished(iteration, run); ++iteration)
      if (!impl_->iterate(iteration, run)) break;
    impl_->finish(run);
  } while (impl_->escape(iteration, run));
  run.result.seconds = seconds_since(start);
  return run.result;
}

// Every iteration starts right after a rebase: here, and after each step
// (so that the gradient of the rebased state serves both the convergence
// test and the next iteration). Reports the start as iteration 0.
void NewtonSolver::Impl::start(NewtonRun& run) {
  run.factorizations_at_start = factorizations();
  objective.rebase();
  evaluator.sync();
  evaluator.clear_failures();
  system.prepare_hessian();
  system.set_mass(objective.mass());
  system.set_deferral(options.line_search == LineSearch::Kinsol ? NewtonSystem::Deferral::Never
                      : options.line_search == LineSearch::Energy
                          ? NewtonSystem::Deferral::Always
                          : NewtonSystem::Deferral::ShiftedSteps);
  run.report.energy = objective.energy();
  run.report.gradient_measure =
      weighted_max_norm(objective.gradient_weights(), evaluator.gradient());
  if (run.callbacks.on_iteration) run.callbacks.on_iteration(run.report);
}

bool NewtonSolver::Impl::finished(int iteration, NewtonRun& run) {
  IterationCheck check;
  check.iterations = iteration;
  check.energy = run.report.energy;
  check.gradient_measure = run.report.gradient_measure;
  check.converged = run.report.gradient_measure <= options.gradient_tolerance;
  if (run.stagnant) check.stagnation = "the step fell below the scaled step tolerance";
  return iteration_finished(check, run.callbacks.stop,
                            options.max_iterations + run.iterations_at_escape, run.result);
}

// One iteration from the current state: KINSOL's (with the Hessian's
// factorization), the step (KINSOL's or the energy line search), then the
// rebase and the report. Returns false, with the result set and the
// objective at the last good state, when the solve must end.
bool NewtonSolver::Impl::iterate(int iteration, NewtonRun& run) {
  const Clock::time_point iteration_start = Clock::now();
  const long factorizations_before = factorizations();
  const Eigen::VectorXd q0 = evaluator.position();
  const Eigen::VectorXd weights = objective.gradient_weights();
  as_eigen(f_scale.get()) = weights.cwiseAbs().cwiseMax(kMinimumScale);
  int flag = kinsol_step(q0);
  run.report.energy_line_search = false;
  run.report.chord_corrections = 0;
  double accepted_energy = 0.0;  // known after an energy line search step
  if (flag == KIN_LSETUP_FAIL && system.deferred()) {
    // The (possibly shifted) factorization is ready: step on the energy.
    run.report.energy_line_search = true;
    if (!energy_step(q0, weights, run, accepted_energy)) return false;
    flag = KIN_SUCCESS;
  }
  const bool accepted =
      flag == KIN_SUCCESS || flag == KIN_MAXITER_REACHED || flag == KIN_INITIAL_GUESS_OK;
  if (!accepted) {
    restore(q0);
    classify_failure(flag, evaluator, system, last_message, run.result);
    return false;
  }
  if (!accept_step(iteration, q0, accepted_energy, run)) return false;
  // KINSOL's own steps leave no linearized forces: the exact Hessian next.
  if (!run.report.energy_line_search) objective.use_exact_hessian();
  // The rebase moves nothing (the energy stays), but re-expresses q.
  objective.rebase();
  evaluator.sync();
  system.prepare_hessian();
  NewtonReport& report = run.report;
  report.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
  report.factorizations = factorizations() - factorizations_before;
  report.shifted = system.any_shift();
  report.shift = system.max_shift();
  report.seconds = seconds_since(iteration_start);
  report.hessian_seconds = system.hessian_seconds();
  report.factorization_seconds = system.factorization_seconds();
  if (run.callbacks.on_iteration) run.callbacks.on_iteration(report);
  return true;
}

// One KINSol call (one iteration) from q0; returns its flag.
int NewtonSolver::Impl::kinsol_step(const Eigen::VectorXd& q0) {
  as_eigen(u.get()) = q0;
  system.reset_iteration_flags();
  evaluator.clear_failures();
  const int flag = KINSol(kinsol.get(), u.get(), KIN_LINESEARCH, u_scale.get(), f_scale.get());
  rethrow_if_fatal(q0);
  return flag;
}

// The step with the factorization that KINSOL's setup left: the energy line
// search (descent_step.hpp), after a full unshifted step its chord
// corrections. On success u holds the new point and `energy` its energy;
// otherwise the result is set and the objective back at q0.
bool NewtonSolver::Impl::energy_step(const Eigen::VectorXd& q0, const Eigen::VectorXd& weights,
                                     NewtonRun& run, double& energy) {
  evaluator.move_to(q0);
  const Eigen::VectorXd g0 = evaluator.gradient();
  DescentStepOptions descent;
  descent.max_step = run.step_cap;
  descent.follow_path = options.follow_path;
  descent.newton_step = !system.last_factorization().shifted;
  descent.mixed_hessian = options.mixed_hessian;
  const DescentStepResult step =
      energy_descent_step(evaluator, system.cholesky(), q0, run.report.energy, g0, descent);
  rethrow_if_fatal(q0);
  if (!step.accepted) {
    restore(q0);
    fail_line_search(step, evaluator, "Newton step", run.result);
    return false;
  }
  energy = step.energy;
  if (options.grow_step_cap) {
    const double taken = (evaluator.position() - q0).norm();
    run.step_cap =
        grown_step_cap(run.step_cap, step.capped, options.max_step, taken, step.step_fraction);
  }
  if (options.max_chord_corrections > 0 && descent.newton_step && step.step_fraction == 1.0 &&
      !step.capped)
    correct_by_chords(weights, run, energy);
  as_eigen(u.get()) = evaluator.position();
  return true;
}

// Chord corrections (chord_correction.hpp) from the evaluator's position
// with the iteration's factorization, in the unknowns the step was taken
// in (before the rebase). Updates `energy` and the report's count.
void NewtonSolver::Impl::correct_by_chords(const Eigen::VectorXd& weights, NewtonRun& run,
                                           double& energy) {
  ChordCorrection chord;
  chord.step = [&](const Eigen::VectorXd&, const Eigen::VectorXd& g) {
    return Eigen::VectorXd(-system.cholesky().solve(g));
  };
  chord.measure = [&](const Eigen::VectorXd& g) { return weighted_max_norm(weights, g); };
  chord.tolerance = options.gradient_tolerance;
  chord.max_corrections = options.max_chord_corrections;
  const double m1 = weighted_max_norm(weights, evaluator.gradient());
  const ChordOutcome out =
      xshell::correct_by_chords(evaluator, chord, run.report.gradient_measure, energy, m1);
  energy = out.energy;
  run.report.chord_corrections = out.corrections;
  run.result.chord_corrections += out.corrections;
}

// Moves to KINSOL's (or the line search's) new point in u and reports its
// energy, step and stagnation; false (the state before the step kept) when
// its energy is not finite.
bool NewtonSolver::Impl::accept_step(int iteration, const Eigen::VectorXd& q0, double energy,
                                     NewtonRun& run) {
  NewtonReport& report = run.report;
  const Eigen::Map<Eigen::VectorXd> q = as_eigen(u.get());
  evaluator.move_to(q);
  report.iteration = iteration + 1;
  report.energy = report.energy_line_search ? energy : objective.energy();
  if (!std::isfinite(report.energy)) {
    // KINSOL's line search watches the gradient only: a step to a point
    // with a finite gradient but no finite energy is not a good state.
    restore(q0);
    report.energy = run.result.energy;
    run.result.status = SolveStatus::NonFinite;
    run.result.reason = "the energy is not finite after the step of iteration " +
                        std::to_string(iteration + 1) + "; the state before it is kept";
    return false;
  }
  report.step_norm = (q - q0).lpNorm<Eigen::Infinity>();
  // KINSOL applies its own stagnation test to the steps it takes.
  run.stagnant =
      report.energy_line_search && scaled_step_length(q, q0) <= options.scaled_step_tolerance;
  return true;
}

// Back to the last good state.
void NewtonSolver::Impl::restore(const Eigen::VectorXd& q0) {
  objective.set(q0);
  evaluator.sync();
}

// An unexpected exception in a callback: back to q0 (best effort), then rethrow.
void NewtonSolver::Impl::rethrow_if_fatal(const Eigen::VectorXd& q0) {
  if (!evaluator.has_fatal()) return;
  try {
    objective.set(q0);
  } catch (...) {
  }
  evaluator.rethrow_if_fatal();
}

void NewtonSolver::Impl::finish(NewtonRun& run) {
  objective.use_exact_hessian();  // stability is the exact Hessian's
  if (run.result.status != SolveStatus::NonFinite)
    run.result.stable = is_positive_definite(system.cholesky(), objective.hessian());
  run.result.factorizations = factorizations() - run.factorizations_at_start;
}

// At a converged state that is not stable: the escape along negative
// curvature (saddle_escape.hpp), reported as one more iteration. True when
// the solver left a saddle and iterates on.
bool NewtonSolver::Impl::escape(int& iteration, NewtonRun& run) {
  NewtonResult& result = run.result;
  if (!options.escape.enabled || !result.converged() || result.stable ||
      static_cast<int>(result.saddles_escaped.size()) >= options.escape.max_escapes)
    return false;
  const Clock::time_point escape_start = Clock::now();
  const long factorizations_before = factorizations();
  const Eigen::VectorXd q_saddle = objective.get();
  const EscapeResult left = escape_saddle(objective, objective.hessian(), objective.mass(),
                                          system.cholesky(), options.escape);
  if (left.outcome != EscapeOutcome::Escaped) {
    evaluator.sync();
    return false;
  }
  result.saddles_escaped.push_back(left.saddle);
  result.status = SolveStatus::IterationLimit;  // set again by the next convergence test
  const double step_norm = (objective.get() - q_saddle).lpNorm<Eigen::Infinity>();
  objective.rebase();
  evaluator.sync();
  system.prepare_hessian();
  NewtonReport& report = run.report;
  report.iteration = ++iteration;
  run.iterations_at_escape = iteration;
  report.energy = objective.energy();
  report.gradient_measure = weighted_max_norm(objective.gradient_weights(), evaluator.gradient());
  report.step_norm = step_norm;
  report.factorizations = factorizations() - factorizations_before;
  report.hessian_seconds = report.factorization_seconds = 0.0;
  report.shifted = true;
  report.energy_line_search = true;
  report.chord_corrections = 0;
  report.seconds = seconds_since(escape_start);
  if (run.callbacks.on_iteration) run.callbacks.on_iteration(report);
  run.stagnant = false;
  return true;
}

NewtonResult solve_newton(Objective& objective, const NewtonOptions& options,
                          const NewtonCallbacks& callbacks) {
  return NewtonSolver(objective, options).solve(callbacks);
}

}  // namespace xshell
