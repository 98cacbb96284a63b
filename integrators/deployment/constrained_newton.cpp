#include "integrators/deployment/constrained_newton.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"
#include "integrators/newton/chord_correction.hpp"
#include "integrators/newton/descent_step.hpp"
#include "integrators/newton/iteration_checks.hpp"

namespace xshell {

namespace {

// Round-off floor: the measure has not halved for kStalledIterations
// iterations while the energy no longer changes.
constexpr int kStalledIterations = 5;
// A solve stagnated there (either test) within this factor (twice) of the
// gradient tolerance has converged as far as round-off lets it: the largest design
// at 10 edges per segment has its floor near 1.1e-6, against the default
// tolerance of 1e-6, and its deployment steps would otherwise fail there
// and be halved.
constexpr double kFloorFactor = 2.0;

// Converging to a saddle (docs/model.md 9.5): two shifted steps in a row,
// the last one lowering the measure by less than kLinearRate (a shifted
// Newton step converges linearly), to below kNearCritical of the solve's
// start.
constexpr double kLinearRate = 0.01;
constexpr double kNearCritical = 1e-3;

// The state of one solve() between its steps.
struct ConstrainedRun {
  ConstrainedRun(double target, const NewtonCallbacks& callbacks, double constraint_tolerance,
                 int max_saddle_escapes)
      : target(target),
        callbacks(callbacks),
        constraint_tolerance(constraint_tolerance),
        max_saddle_escapes(max_saddle_escapes) {}
  double target;  // A
  const NewtonCallbacks& callbacks;
  double constraint_tolerance;
  int max_saddle_escapes;
  ConstrainedNewtonResult result;
  NewtonReport report;    // of the last iteration (or the start)
  Eigen::VectorXd mass;   // at the start
  int iteration = 0;      // iterations done (saddle escapes included)
  bool stagnant = false;  // the last step was below the scaled step tolerance
  double best_measure = 0.0;
  int stalled = 0;  // iterations since the measure last halved, at a constant energy
  long factorizations_at_start = 0;
  // Iterations done when the last saddle was left: the iteration limit
  // counts from there (the descent from a saddle is a solve of its own).
  long iterations_at_escape = 0;
  // The cap on the step's 2-norm: options.max_step, or with
  // options.grow_step_cap doubled after every capped step taken in full
  // and back to the length of the last step when the line search had to
  // shorten it (grown_step_cap).
  double step_cap = 0.0;
  bool capped = false;  // the last step was scaled down to step_cap
  // The iteration before the last: its step was shifted, and the measure
  // it started from.
  bool previous_shifted = false;
  double previous_measure = 0.0;
  double start_measure = 0.0;
  bool early_escape_tried = false;  // once per solve
  bool full_step = false;           // the last line search took the step in full (not expanded)
};

// The Newton step p and its multiplier tau.
struct ConstrainedStep {
  Eigen::VectorXd p;
  double tau = 0.0;
  Eigen::VectorXd x2;  // H^-1 a, when the Schur complement made the step (else empty)
};

}  // namespace

struct ConstrainedNewtonSolver::Impl {
  Objective& objective;
  const AverageConstraint& constraint;
  const NewtonOptions& options;
  ObjectiveEvaluator evaluator;
  CholeskySolver full;     // H, for the Schur complement
  CholeskySolver reduced;  // B^T H B, for the fallback and the stability test
  ShiftMemory shift_memory;
  // What the stability test factorized, unshifted, at the final state of
  // the last solve: tangent() reuses it while the configuration is the same.
  struct FinalFactorization {
    Eigen::VectorXd q;  // empty: none
    bool full = false, reduced = false;
  } final_factorization;
  // What the last tangent() solved with: second_derivative() may reuse it
  // while no factorization has been made since.
  struct TangentFactorization {
    long factorizations = -1;  // factorizations() after it; -1: none
    bool full = false;         // H's (else B^T H B's)
    Eigen::VectorXd t;
  } tangent_factorization;
  Impl(Objective& objective, const AverageConstraint& constraint, const NewtonOptions& options)
      : objective(objective),
        constraint(constraint),
        options(options),
        evaluator(objective),
        shift_memory(options.shift) {}
  // B^T H B, shifted by multiples of diag(B^T M B) when indefinite.
  ShiftedFactorization factorize_reduced(const Eigen::SparseMatrix<double>& H,
                                         const Eigen::VectorXd& mass) {
    const ShiftedFactorization f =
        factorize_with_shift(reduced, constraint.reduce(H), constraint.reduce_diagonal(mass),
                             options.shift, shift_memory.first_tau());
    shift_memory.record(f);
    return f;
  }
  bool final_factorization_here() const {
    const FinalFactorization& f = final_factorization;
    return f.q.size() == objective.size() && f.q == objective.get();
  }
  void stability_test(ConstrainedRun& run);
  long factorizations() const {
    return full.stats().factorizations + reduced.stats().factorizations;
  }
  // The convergence measure: max_i |w_i (g - tau a)_i| with the least-squares tau.
  double measure(const Eigen::VectorXd& w, const Eigen::VectorXd& g) const {
    return weighted_max_norm(w, constraint.projected(g));
  }
  void start(ConstrainedRun& run);
  bool finished(ConstrainedRun& run);
  bool iterate(ConstrainedRun& run);
  bool direction(ConstrainedRun& run, const Eigen::SparseMatrix<double>& H,
                 const Eigen::VectorXd& g0, double c, ConstrainedStep& step);
  bool line_search(ConstrainedRun& run, const Eigen::VectorXd& q0, double e0,
                   const Eigen::VectorXd& g0, double c, const Eigen::VectorXd& w,
                   const ConstrainedStep& step);
  void record_step(ConstrainedRun& run, const Eigen::VectorXd& q0, double e0,
                   const Eigen::VectorXd& w);
  void correct_by_chords(ConstrainedRun& run, const ConstrainedStep& step,
                         const Eigen::VectorXd& q0, const Eigen::VectorXd& w);
  bool escape(ConstrainedRun& run);
  bool converging_to_saddle(const ConstrainedRun& run) const;
  bool leave_saddle(ConstrainedRun& run);
  bool escape_saddle(ConstrainedRun& run);
  void finish(ConstrainedRun& run);
};

ConstrainedNewtonSolver::ConstrainedNewtonSolver(Objective& objective,
                                                 const AverageConstraint& constraint,
                                                 NewtonOptions options)
    : objective_(objective),
      constraint_(constraint),
      options_(options),
      impl_(std::make_unique<Impl>(objective, constraint, options_)) {
  max_saddle_escapes = options_.escape.enabled ? options_.escape.max_escapes : 0;
  if (objective.size() != constraint.size())
    throw std::invalid_argument("constrained Newton: the constraint does not fit the objective");
}

ConstrainedNewtonSolver::~ConstrainedNewtonSolver() = default;

ConstrainedNewtonResult ConstrainedNewtonSolver::solve(double target,
                                                       const NewtonCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  Impl& s = *impl_;
  ConstrainedRun run(target, callbacks, constraint_tolerance, max_saddle_escapes);
  run.step_cap = s.options.max_step;
  const ExactHessianAtExit exact_at_exit(objective_);
  s.start(run);
  run.result.setup_seconds = seconds_since(start);
  do {  // iterations, and again after each escape from a saddle
    while (!s.finished(run) && s.iterate(run)) {
      ++run.iteration;
      if (s.converging_to_saddle(run)) {
        run.early_escape_tried = true;
        s.leave_saddle(run);
      }
    }
  } while (s.escape(run));
  s.finish(run);
  run.result.seconds = seconds_since(start);
  return run.result;
}

// Reports the start as iteration 0.
void ConstrainedNewtonSolver::Impl::start(ConstrainedRun& run) {
  run.factorizations_at_start = factorizations();
  final_factorization.q.resize(0);
  evaluator.sync();
  evaluator.clear_failures();
  run.mass = objective.mass();
  run.report.energy = objective.energy();
  run.report.gradient_measure = measure(objective.gradient_weights(), evaluator.gradient());
  if (run.callbacks.on_iteration) run.callbacks.on_iteration(run.report);
  run.best_measure = run.report.gradient_measure;
  run.start_measure = run.report.gradient_measure;
}

bool ConstrainedNewtonSolver::Impl::finished(ConstrainedRun& run) {
  const double residual = run.target - constraint.value(objective.get());
  IterationCheck check;
  check.iterations = run.iteration;
  check.energy = run.report.energy;
  check.gradient_measure = run.report.gradient_measure;
  check.converged = run.report.gradient_measure <= options.gradient_tolerance &&
                    std::abs(residual) <= run.constraint_tolerance;
  if (run.stagnant)
    check.stagnation = "the step fell below the scaled step tolerance";
  else if (run.stalled >= kStalledIterations)
    check.stagnation =
        "no progress in " + std::to_string(kStalledIterations) + " iterations at a constant energy";
  const bool at_floor = !check.stagnation.empty() && !check.converged &&
                        std::abs(residual) <= run.constraint_tolerance &&
                        check.gradient_measure <= kFloorFactor * options.gradient_tolerance;
  check.converged = check.converged || at_floor;
  const bool done = iteration_finished(
      check, run.callbacks.stop, options.max_iterations + run.iterations_at_escape, run.result);
  run.result.at_round_off_floor = at_floor && run.result.converged();
  if (run.result.at_round_off_floor)
    run.result.reason = "gradient measure " + scientific(check.gradient_measure) +
                        " at its round-off floor, within twice the tolerance (" + check.stagnation +
                        ")";
  return done;
}

// One iteration after a rebase: the step (Schur complement, or the null
// space), its line search, the report. Returns false, with the result set
// and the objective at the last good state, when the solve must end.
bool ConstrainedNewtonSolver::Impl::iterate(ConstrainedRun& run) {
  const Clock::time_point iteration_start = Clock::now();
  const long factorizations_before = factorizations();
  objective.rebase();
  evaluator.sync();
  const Eigen::VectorXd q0 = objective.get();
  const Eigen::VectorXd w = objective.gradient_weights();
  // The Hessian first: the linkage's pass gives the gradient with it.
  const Eigen::SparseMatrix<double>& H = objective.hessian();
  const Eigen::VectorXd g0 = evaluator.gradient();
  const double e0 = objective.energy();
  const double c = run.target - constraint.value(q0);
  run.previous_shifted = run.report.shifted;
  run.previous_measure = run.report.gradient_measure;
  ConstrainedStep step;
  if (!direction(run, H, g0, c, step)) return false;
  if (!line_search(run, q0, e0, g0, c, w, step)) return false;
  record_step(run, q0, e0, w);
  run.report.chord_corrections = 0;
  if (options.max_chord_corrections > 0 && step.x2.size() && run.full_step && !run.capped)
    correct_by_chords(run, step, q0, w);
  run.report.factorizations = factorizations() - factorizations_before;
  run.report.seconds = seconds_since(iteration_start);
  if (run.callbacks.on_iteration) run.callbacks.on_iteration(run.report);
  return true;
}

// The Newton step from gradient g0 and constraint residual c: by the Schur
// complement when H is positive definite, else on the constraint's null
// space (the header). Its length is capped at run.step_cap. False, with the
// result set, when no finite step could be made.
bool ConstrainedNewtonSolver::Impl::direction(ConstrainedRun& run,
                                              const Eigen::SparseMatrix<double>& H,
                                              const Eigen::VectorXd& g0, double c,
                                              ConstrainedStep& step) {
  const Eigen::VectorXd& a = constraint.coefficients();
  ConstrainedNewtonResult& result = run.result;
  run.report.shifted = false;
  run.report.shift = 0.0;
  final_factorization.q.resize(0);
  const FactorizationStatus status = full.factorize(H);
  if (status == FactorizationStatus::NonFinite) {
    result.status = SolveStatus::NonFinite;
    result.reason = "the Hessian is not finite";
    return false;
  }
  if (status == FactorizationStatus::PositiveDefinite) {
    // Schur complement: two solves with the one factorization.
    const Eigen::VectorXd x1 = full.solve(g0), x2 = full.solve(a);
    step.tau = (c + a.dot(x1)) / a.dot(x2);
    step.p = step.tau * x2 - x1;
    step.x2 = x2;
    ++result.schur_iterations;
  } else {
    const ShiftedFactorization f = factorize_reduced(H, run.mass);
    if (f.status != FactorizationStatus::PositiveDefinite) {
      result.status = f.status == FactorizationStatus::NonFinite ? SolveStatus::NonFinite
                                                                 : SolveStatus::LinearSolverFailed;
      result.reason = "the constrained Hessian could not be factorized even with the largest shift";
      return false;
    }
    // Restore the constraint by the minimal shift d0, then Newton on the
    // plane with the gradient extrapolated there: g0 + H d0.
    const Eigen::VectorXd d0 = (c / a.squaredNorm()) * a;
    const Eigen::VectorXd g_shifted = c != 0.0 ? Eigen::VectorXd(g0 + H * d0) : g0;
    step.p = constraint.expand(-reduced.solve(constraint.restrict(g_shifted))) + d0;
    step.tau = constraint.multiplier(g0);
    run.report.shifted = f.shifted;
    run.report.shift = f.shift;
    ++result.null_space_iterations;
  }
  const double length = step.p.norm();
  if (!std::isfinite(length)) {
    result.status = SolveStatus::NonFinite;
    result.reason = "the Newton step is not finite";
    return false;
  }
  run.capped = length > run.step_cap;
  if (run.capped) step.p *= run.step_cap / length;
  return true;
}

// Armijo backtracking from q0 along p, or along the objective's curve
// (NewtonOptions::follow_path), (descent_step.hpp) on the exact penalty
// merit
//   phi(q) = E(q) + mu |a . q - A|:
// the energy itself on the constraint's plane (where both steps descend:
// g . p = -r^T K^-1 r < 0), and from a start off the plane, where the
// energy may have to rise to restore the constraint, a merit that the step
// decreases when mu > max(|tau|, g . p / |c|) (here twice that): its
// slope is g . p - mu |c| < 0. Accepts phi(q0 + t p) <= phi(q0) + c1 t
// min(slope, 0) (+ round-off slack), or, in the end game, the full step
// when it lowers |diag(w) (g - tau a)|. False, with the result set and the
// objective back at q0, when no step was accepted.
bool ConstrainedNewtonSolver::Impl::line_search(ConstrainedRun& run, const Eigen::VectorXd& q0,
                                                double e0, const Eigen::VectorXd& g0, double c,
                                                const Eigen::VectorXd& w,
                                                const ConstrainedStep& step) {
  DescentStepOptions descent;
  descent.max_step = options.max_step;
  const double r0 = (w.array() * constraint.projected(g0).array()).matrix().norm();
  DescentStepResult accepted;
  try {
    const double gp = g0.dot(step.p);
    const double mu =
        c == 0.0 ? 0.0 : 2.0 * std::max(std::abs(step.tau), std::max(gp, 0.0) / std::abs(c));
    BacktrackingMerit penalty;
    penalty.merit = [&](double energy, const Eigen::VectorXd& q) {
      return energy + mu * std::abs(constraint.value(q) - run.target);
    };
    penalty.phi0 = penalty.merit(e0, q0);
    penalty.slope = std::min(gp - mu * std::abs(c), 0.0);
    penalty.progress = [&] {
      const Eigen::VectorXd g = evaluator.gradient();
      return g.allFinite() && (w.array() * constraint.projected(g).array()).matrix().norm() < r0;
    };
    // The linkage's curve (docs/model.md 9.8), joints placed, on steps of an
    // unshifted Hessian (H's or B^T H B's); shifted steps keep the line.
    if (options.follow_path && !run.report.shifted)
      penalty.path = objective_path(evaluator, q0, step.p, true);
    // Newton's mixed Hessian (NewtonOptions::mixed_hessian) after the
    // steps along the curve; the line's keep the exact one.
    if (options.mixed_hessian && penalty.path)
      objective.use_mixed_hessian(step.p);
    else
      objective.use_exact_hessian();
    accepted = backtrack_on_energy(evaluator, q0, e0, step.p, penalty, descent);
  } catch (...) {
    objective.set(q0);
    throw;
  }
  run.full_step = accepted.accepted && accepted.step_fraction == 1.0;
  if (accepted.accepted) {
    if (options.grow_step_cap)
      run.step_cap = grown_step_cap(run.step_cap, run.capped, options.max_step,
                                    accepted.step_fraction * step.p.norm(), accepted.step_fraction);
    return true;
  }
  objective.set(q0);
  evaluator.sync();
  fail_line_search(accepted, evaluator, "constrained Newton step", run.result);
  return false;
}

// Reports the accepted step from q0 and updates the stagnation tests.
void ConstrainedNewtonSolver::Impl::record_step(ConstrainedRun& run, const Eigen::VectorXd& q0,
                                                double e0, const Eigen::VectorXd& w) {
  NewtonReport& report = run.report;
  const Eigen::VectorXd q = objective.get();
  report.iteration = run.iteration + 1;
  report.energy = objective.energy();
  report.gradient_measure = measure(w, evaluator.gradient());
  report.step_norm = (q - q0).lpNorm<Eigen::Infinity>();
  report.energy_line_search = true;
  run.stagnant = scaled_step_length(q, q0) <= options.scaled_step_tolerance;
  if (report.gradient_measure < 0.5 * run.best_measure) {
    run.best_measure = report.gradient_measure;
    run.stalled = 0;
  } else if (std::abs(report.energy - e0) <= 1e-13 * std::abs(e0)) {
    ++run.stalled;
  }
}

// Chord corrections (chord_correction.hpp) after a full step of the Schur
// complement, with its factorization of H: the bordered system's solution
// from the gradient and constraint residual at each point.
void ConstrainedNewtonSolver::Impl::correct_by_chords(ConstrainedRun& run,
                                                      const ConstrainedStep& step,
                                                      const Eigen::VectorXd& q0,
                                                      const Eigen::VectorXd& w) {
  const Eigen::VectorXd& a = constraint.coefficients();
  ChordCorrection chord;
  chord.step = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& g) {
    const Eigen::VectorXd x1 = full.solve(g);
    const double tau = (run.target - constraint.value(q) + a.dot(x1)) / a.dot(step.x2);
    return Eigen::VectorXd(tau * step.x2 - x1);
  };
  chord.measure = [&](const Eigen::VectorXd& g) { return measure(w, g); };
  chord.tolerance = options.gradient_tolerance;
  chord.max_corrections = options.max_chord_corrections;
  NewtonReport& report = run.report;
  const ChordOutcome out = xshell::correct_by_chords(evaluator, chord, run.previous_measure,
                                                     report.energy, report.gradient_measure);
  if (out.corrections == 0) return;
  report.chord_corrections = out.corrections;
  run.result.chord_corrections += out.corrections;
  report.energy = out.energy;
  report.gradient_measure = out.measure;
  report.step_norm = (objective.get() - q0).lpNorm<Eigen::Infinity>();
  if (out.measure < 0.5 * run.best_measure) {
    run.best_measure = out.measure;
    run.stalled = 0;
  }
}

// After the iterations ended: the stability test, and at a converged but
// unstable state (a saddle) the escape along negative curvature. True when
// the solver escaped and iterates on.
bool ConstrainedNewtonSolver::Impl::escape(ConstrainedRun& run) {
  ConstrainedNewtonResult& result = run.result;
  if (result.status != SolveStatus::NonFinite) stability_test(run);
  if (!result.converged() || result.stable) return false;
  return leave_saddle(run);
}

// The iterates are converging to a saddle (kLinearRate, kNearCritical):
// shifted steps converge to it only linearly, and when it is symmetric
// (a flat shell about to buckle, its gradient without a component along
// the buckling mode) they cannot leave it. The escape need not wait for
// convergence (on manta_ray's deployment it came 4 iterations earlier).
bool ConstrainedNewtonSolver::Impl::converging_to_saddle(const ConstrainedRun& run) const {
  const double m = run.report.gradient_measure;
  return !run.early_escape_tried && run.report.shifted && run.previous_shifted &&
         m > kLinearRate * run.previous_measure && m < kNearCritical * run.start_measure &&
         m > options.gradient_tolerance;
}

// Leaves the state downhill along negative curvature (escape_saddle) and
// reports that as an iteration. False, the state unchanged, when there is
// no negative curvature or the solve's escapes are used up.
bool ConstrainedNewtonSolver::Impl::leave_saddle(ConstrainedRun& run) {
  ConstrainedNewtonResult& result = run.result;
  if (result.saddle_escapes >= run.max_saddle_escapes) return false;
  objective.use_exact_hessian();  // its negative curvature
  const Clock::time_point escape_start = Clock::now();
  const long factorizations_at_escape = factorizations();
  const Eigen::VectorXd q_saddle = objective.get();
  if (!escape_saddle(run)) return false;
  ++result.saddle_escapes;
  ++run.iteration;
  run.iterations_at_escape = run.iteration;
  evaluator.sync();
  NewtonReport& report = run.report;
  report.iteration = run.iteration;
  report.energy = objective.energy();
  report.gradient_measure = measure(objective.gradient_weights(), evaluator.gradient());
  report.step_norm = (objective.get() - q_saddle).lpNorm<Eigen::Infinity>();
  report.shifted = true;
  report.chord_corrections = 0;
  report.factorizations = factorizations() - factorizations_at_escape;
  report.seconds = seconds_since(escape_start);
  if (run.callbacks.on_iteration) run.callbacks.on_iteration(report);
  run.stagnant = false;
  run.best_measure = report.gradient_measure;
  run.stalled = 0;
  result.stable = false;
  return true;
}

// stable: an unshifted LL^T of B^T H B succeeds. When H itself is positive
// definite so is B^T H B (B has full column rank), and H's factorization is
// what tangent() needs next: H is tried first, B^T H B only when H fails.
void ConstrainedNewtonSolver::Impl::stability_test(ConstrainedRun& run) {
  objective.use_exact_hessian();
  const Eigen::SparseMatrix<double>& H = objective.hessian();
  FinalFactorization& f = final_factorization;
  f.full = full.factorize(H) == FactorizationStatus::PositiveDefinite;
  f.reduced = f.full || is_positive_definite(reduced, constraint.reduce(H));
  f.q = objective.get();
  run.result.stable = f.reduced;
}

void ConstrainedNewtonSolver::Impl::finish(ConstrainedRun& run) {
  const Eigen::VectorXd g = objective.gradient();
  run.result.multiplier = constraint.multiplier(g);
  run.result.constraint_residual = run.target - constraint.value(objective.get());
  run.result.factorizations = factorizations() - run.factorizations_at_start;
}

// The lowest mode of B^T H B (mass diag(B^T M B), shift-invert on the
// reduced solver's analysis; saddle_escape.hpp), signed by the branch bias
// carried to z, and the step downhill along B z. Records the saddle.
bool ConstrainedNewtonSolver::Impl::escape_saddle(ConstrainedRun& run) {
  const Eigen::SparseMatrix<double> Hz = constraint.reduce(objective.hessian());
  const Eigen::VectorXd Mz = constraint.reduce_diagonal(run.mass);
  SaddleEscapeOptions escape = options.escape;
  if (escape.bias.size() == objective.size())
    escape.bias = constraint.restrict(options.escape.bias);
  else
    escape.bias.resize(0);
  const double e0 = objective.energy();
  const NegativeMode mode = negative_mode(Hz, Mz, reduced, escape);
  if (!mode.found || !mode.negative) return false;
  Eigen::VectorXd d = constraint.expand(mode.vector);
  const double scale = d.lpNorm<Eigen::Infinity>();
  d /= scale;  // largest entry of magnitude 1, the sign kept
  // The bend on the null space (z = mode / scale: d = B z), carried back.
  const Eigen::VectorXd third = third_derivative_along(objective, d);
  const Eigen::VectorXd wz =
      bend_of_mode(Hz, Mz, mode.eigenvalue, mode.vector / scale,
                   third.size() ? constraint.restrict(third) : third, reduced);
  const Eigen::VectorXd bend = wz.size() ? constraint.expand(wz) : wz;
  if (!(step_downhill(objective, d, escape, bend) > 0.0)) return false;
  SaddleRecord saddle;
  saddle.energy = e0;
  saddle.lowest_eigenvalue = mode.eigenvalue;
  run.result.saddles_escaped.push_back(saddle);
  return true;
}

long ConstrainedNewtonSolver::factorizations() const { return impl_->factorizations(); }

Eigen::VectorXd ConstrainedNewtonSolver::tangent() {
  Impl& s = *impl_;
  const Eigen::VectorXd& a = constraint_.coefficients();
  const Eigen::SparseMatrix<double>& H = objective_.hessian();
  const bool reuse = s.final_factorization_here();
  Impl::TangentFactorization& used = s.tangent_factorization;
  used.factorizations = -1;
  if (reuse ? s.final_factorization.full
            : s.full.factorize(H) == FactorizationStatus::PositiveDefinite) {
    const Eigen::VectorXd x = s.full.solve(a);
    used = {s.factorizations(), true, x / a.dot(x)};
    return used.t;
  }
  if (!(reuse && s.final_factorization.reduced) &&
      s.factorize_reduced(H, objective_.mass()).status != FactorizationStatus::PositiveDefinite)
    return {};
  s.final_factorization.q.resize(0);  // its solvers now hold other matrices
  const Eigen::VectorXd t0 = a / a.squaredNorm();
  const Eigen::VectorXd Ht0 = H * t0;
  used = {s.factorizations(), false,
          t0 - constraint_.expand(s.reduced.solve(constraint_.restrict(Ht0)))};
  return used.t;
}

Eigen::VectorXd ConstrainedNewtonSolver::second_derivative(const Eigen::VectorXd& third) {
  Impl& s = *impl_;
  const Impl::TangentFactorization& used = s.tangent_factorization;
  if (used.factorizations < 0 || used.factorizations != s.factorizations() ||
      third.size() != objective_.size())
    return {};
  if (!used.full) return -constraint_.expand(s.reduced.solve(constraint_.restrict(third)));
  const Eigen::VectorXd x = s.full.solve(third);
  return -(x - constraint_.coefficients().dot(x) * used.t);
}

Eigen::VectorXd ConstrainedNewtonSolver::adjoint(const Eigen::VectorXd& f) {
  Impl& s = *impl_;
  s.final_factorization.q.resize(0);
  const Eigen::VectorXd& a = constraint_.coefficients();
  const Eigen::SparseMatrix<double>& H = objective_.hessian();
  if (s.full.factorize(H) == FactorizationStatus::PositiveDefinite) {
    const Eigen::VectorXd x1 = s.full.solve(f), x2 = s.full.solve(a);
    return x1 - (a.dot(x1) / a.dot(x2)) * x2;
  }
  if (s.reduced.factorize(constraint_.reduce(H)) != FactorizationStatus::PositiveDefinite)
    return {};
  return constraint_.expand(s.reduced.solve(constraint_.restrict(f)));
}

}  // namespace xshell
