#include "integrators/dynamics/ida_dynamics_run.hpp"

#include <ida/ida.h>
#include <ida/ida_ls.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/dynamics/ida_endgame.hpp"
#include "integrators/dynamics/mass_and_damping.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"
#include "integrators/newton/newton.hpp"

namespace xshell {

namespace {

// A step shorter than this fraction of the simulated time means the
// integrator is creeping towards a barrier (configurations it cannot
// evaluate) and no longer advances time in floating point.
constexpr double kStagnantStepRatio = 1e-12;

}  // namespace

DynamicsRun::DynamicsRun(Objective& target, const DynamicsOptions& run_options,
                         const DynamicsCallbacks& run_callbacks, Clock::time_point started)
    : objective(target),
      options(run_options),
      callbacks(run_callbacks),
      start(started),
      n(target.size()),
      second_order(run_options.form == DynamicsForm::SecondOrder),
      evaluator(target),
      system(set_up_mass_and_damping()) {
  set_up_state();
}

// Mass and damping from the starting configuration (one Hessian for both);
// called while the members up to `system` are initialized, to build it.
DynamicsSystem DynamicsRun::set_up_mass_and_damping() {
  evaluator.sync();
  const Eigen::SparseMatrix<double>& H0 = objective.hessian();
  mass = options.mass == MassModel::Physical ? objective.mass() : fictitious_mass(H0);
  choice = choose_damping(options, estimator, H0, mass);
  result.damping = choice.c;
  result.stiffness_damping = choice.damping.stiffness_coefficient;
  return DynamicsSystem(evaluator, options.form, mass, choice.damping);
}

// Initial state at rest, and its report (step 0).
void DynamicsRun::set_up_state() {
  y.resize(system.size());
  y.head(n) = objective.get();
  if (second_order) y.tail(n).setZero();
  weights = objective.gradient_weights();
  scales =
      options.error_control.scaled_tolerances ? unknown_scales(weights) : Eigen::VectorXd::Ones(n);
  energy0 = objective.energy();
  report.energy = energy0;
  report.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
}

// The start velocity on the slow manifold (DynamicsStartOptions). From an
// indefinite Hessian (choice.unstable) the slow manifold does not attract
// along the unstable modes, and -C^-1 grad E is large along the nearly
// undamped ones: such starts stay at rest.
void DynamicsRun::start_on_slow_manifold() {
  const bool slow_start = second_order && options.start.velocity == DynamicsStart::SlowManifold;
  const bool moving = std::isfinite(report.energy) && std::isfinite(report.gradient_measure) &&
                      report.gradient_measure > options.stopping.gradient_tolerance;
  if (!(slow_start && moving && !choice.unstable && !choice.zero_mode)) return;
  const double inertia =
      options.start.time > 0.0 ? system.damping().rate / options.start.time : 0.0;
  try {
    Eigen::VectorXd v = system.overdamped_velocity(0.0, inertia);
    // The overdamped velocity is the linear model's at the start. Along a
    // (nearly) zero mode, such as the free arm of a tee under gravity, it
    // is huge: it would carry the unknowns far beyond the model's reach
    // within one time constant (1 / rate), and the run would start with a
    // kinetic energy thousands of times the energy there is to release.
    // The velocity is scaled down to move at most start.reach (in units
    // of unknown_scales) in one time constant.
    const double reach = v.cwiseQuotient(scales).cwiseAbs().maxCoeff() / system.damping().rate;
    if (reach > options.start.reach) v *= options.start.reach / reach;
    if (v.allFinite()) {
      y.tail(n) = v;
      on_slow_manifold = true;
    }
  } catch (const std::runtime_error&) {
    // C + M/T not positive definite after all: start at rest.
  }
  report.kinetic_energy = kinetic(y);
}

DynamicsResult DynamicsRun::solve() {
  start_on_slow_manifold();
  if (callbacks.on_step) callbacks.on_step(report);
  if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure)) {
    finish(SolveStatus::NonFinite, "energy or gradient not finite at the start");
  } else if (report.gradient_measure <= options.stopping.gradient_tolerance) {
    finish(SolveStatus::Converged, "in equilibrium at the start");
  } else {
    watch.emplace(report.energy, report.gradient_measure, options.stopping.progress, "steps");
    integrate();
  }
  return final_result();
}

// Damped dynamics, then the end game; again if that fails.
void DynamicsRun::integrate() {
  create_integrator();
  if (options.steps.cap_indefinite)
    system.on_indefinite(
        [this](double cj) { IDASetMaxStep(integrator->ida.get(), step_cap.on_failure(cj)); });
  for (;;) {
    while (advance()) {
    }
    // Leave the objective at the last accepted state.
    evaluator.move_to(y.head(n));
    if (!endgame || !play_endgame()) break;
  }
  accumulate_stats();
  system.on_indefinite(nullptr);
}

// IDA from the initial state, with consistent derivatives and a first step.
void DynamicsRun::create_integrator() {
  const Eigen::VectorXd yp0 = system.consistent_derivatives(y, 0.0);
  integrator.emplace(system, options, y, yp0, absolute_tolerances());
  q_only = second_order && options.error_control.suppress_velocity;
  if (options.start.initial_step <= 0.0) {
    // IDA's own first step is h = 0.5 / |y'|_WRMS (its rule for a distant
    // output time), which sees nothing of a start at rest when the
    // velocities are out of the error test; on the slow manifold, it is
    // sized for a fast layer that this start does not have: begin
    // start.step_factor times longer, or start.rest_step_factor times from
    // rest (second order).
    double h0 = first_step(y, yp0, absolute_tolerances(), options.error_control.relative_tolerance,
                           n, q_only);
    const double factor = !second_order      ? 1.0
                          : on_slow_manifold ? options.start.step_factor
                                             : options.start.rest_step_factor;
    if (factor > 1.0) h0 *= factor;
    if (h0 > 0.0) check_sundials(IDASetInitStep(integrator->ida.get(), h0), "IDASetInitStep");
  }
  time_scale = 1.0 / system.damping().rate;
  total0 = report.energy + report.kinetic_energy;
  last_total = total0;
  last_good = y;
  last_good_t = 0.0;
  t = 0.0;
  rebased_at = y.head(n);
  refreshed_at = y.head(n);
  endgame_on = options.endgame.step_length > 0.0;
}

// One step of IDA, and take_step. Returns false when the dynamics stop:
// the run is finished (result.status set), or the end game is due.
bool DynamicsRun::advance() {
  if (stop_or_limit(callbacks.stop, result.iterations, options.stopping.max_steps, "steps", result))
    return false;
  evaluator.clear_failures();
  const int flag = IDASolve(integrator->ida.get(), t + 1e10 * time_scale, &t, integrator->y.get(),
                            integrator->yp.get(), IDA_ONE_STEP);
  if (evaluator.has_fatal()) {  // an unexpected exception in a callback
    try {
      objective.set(last_good.head(n));
    } catch (...) {
    }
    evaluator.rethrow_if_fatal();
  }
  if (flag < 0) {
    on_integrator_failure(flag);
    return false;
  }
  // Lift the step cap once steps under it kept K positive definite.
  if (step_cap.on_step())
    check_sundials(IDASetMaxStep(integrator->ida.get(), 0.0), "IDASetMaxStep");
  double h = 0.0;
  IDAGetLastStep(integrator->ida.get(), &h);
  y = as_eigen(integrator->y.get());
  return take_step(h);
}

// The step of length h that IDA took to y: its energy, report and checks,
// then the bookkeeping of an accepted step (refresh, rebase). Returns
// false when the dynamics stop, as advance().
bool DynamicsRun::take_step(double h) {
  // IDA's last Newton correction lands on a y it never evaluated. When
  // that y is invalid (a rod's terminal edge through its joint, say),
  // the step is taken again, shorter, as a rejected step. The energy
  // there comes from the same pass as the move.
  double step_energy = 0.0;
  if (evaluator.energy_at(y.data(), &step_energy) != 0) {
    evaluator.rethrow_if_fatal();
    return retry_shorter(
        h, "the objective rejects the accepted state (" + evaluator.last_message() + ")");
  }
  ++result.iterations;
  IDAGetLastOrder(integrator->ida.get(), &report.order);
  report.step = result.iterations;
  report.time = t;
  report.step_size = h;
  report.energy = step_energy;
  report.kinetic_energy = kinetic(y);
  report.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
  const double total = report.energy + report.kinetic_energy;
  if (options.steps.dissipation_guard > 0.0 && std::isfinite(total) &&
      total - last_total > options.steps.dissipation_guard * std::max(total0 - last_total, 0.0) +
                               1e-12 * std::abs(report.energy)) {
    // E + K rose: the step is taken again (see StepControlOptions).
    --result.iterations;
    return retry_shorter(h, "E + K rises");
  }
  if (callbacks.on_step) callbacks.on_step(report);
  if (!step_is_sound(h)) return false;
  // The end game: the motion has died out as far as IDA resolves it
  // and its steps have grown to many time constants. Implicit Euler
  // with an infinite step is a Newton step, so the remaining steps are
  // taken at that limit (Newton with the energy line search), once the
  // Hessian is positive definite (a stable basin, not a saddle). The
  // check factorizes with the estimator's solver: IDA goes on with its
  // factorization of K when the Hessian is indefinite.
  if (endgame_on && h * system.damping().rate >= options.endgame.step_length * endgame_backoff &&
      is_positive_definite(estimator, objective.hessian())) {
    last_good = y;
    endgame = true;
    return false;
  }
  last_good = y;
  last_good_t = t;
  last_total = total;
  if (stops_here()) return false;
  const Progress progress =
      watch->observe(report.energy, report.gradient_measure, report.kinetic_energy);
  if (progress != Progress::Continuing) {
    finish(progress == Progress::Diverging ? SolveStatus::Diverged : SolveStatus::IntegratorFailed,
           watch->reason());
    return false;
  }
  refresh_by_distance(h);
  rebase_if_due(h);
  return true;
}

// IDASolve failed: the result says why, and the state goes back to the
// last accepted one.
void DynamicsRun::on_integrator_failure(int flag) {
  classify_failure(flag, evaluator, system, integrator->last_message, result);
  y = last_good;
  // IDA gave up late in a run whose motion had died out (error tests
  // at the round-off floor of the residual): the end game can still
  // finish it from the last accepted state if that is a stable basin.
  if (endgame_on && t * system.damping().rate >= options.endgame.step_length * endgame_backoff &&
      kinetic(y) <= 1e-6 * std::max(std::abs(energy0 - report.energy), std::abs(report.energy))) {
    evaluator.move_to(y.head(n));
    endgame = is_positive_definite(estimator, objective.hessian());
  }
}

// False, the run finished, when the step of length h left non-finite
// values or no longer advances time.
bool DynamicsRun::step_is_sound(double h) {
  if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure) || !y.allFinite()) {
    finish(SolveStatus::NonFinite,
           "non-finite state after step " + std::to_string(result.iterations));
    y = last_good;
    return false;
  }
  if (h <= kStagnantStepRatio * t) {
    const bool nonfinite = evaluator.last_failure() == EvaluationFailure::NonFinite;
    finish(nonfinite ? SolveStatus::NonFinite : SolveStatus::IntegratorFailed,
           "step size " + scientific(h) + " stagnant at t = " + scientific(t) +
               (evaluator.last_message().empty() ? "" : ": " + evaluator.last_message()));
    return false;
  }
  return true;
}

// The stop criterion on the accepted step; true when the run converged,
// or settled near an equilibrium for the end game to finish
// (EndgameOptions::gradient_factor).
bool DynamicsRun::stops_here() {
  const double energy_scale = std::max(std::abs(energy0 - report.energy), std::abs(report.energy));
  const bool at_rest = report.kinetic_energy <= options.stopping.kinetic_tolerance * energy_scale;
  if (report.gradient_measure <= options.stopping.gradient_tolerance && at_rest) {
    finish(SolveStatus::Converged, "gradient and kinetic energy below tolerance");
    return true;
  }
  if (endgame_on && options.endgame.gradient_factor > 0.0 && at_rest &&
      report.gradient_measure <=
          options.endgame.gradient_factor / endgame_backoff * options.stopping.gradient_tolerance) {
    endgame = true;
    return true;
  }
  if (settled_in_stable_basin(at_rest)) {
    endgame = true;
    return true;
  }
  return false;
}

// EndgameOptions::rest_check_fall: at rest (second order), a positive
// definite H (a factorization by the estimator's solver) hands over to the
// end game as a step of many time constants would: the motion has died out
// in a stable basin, and the remaining steps only creep to its equilibrium
// (scary_face from flat spent its last 5 steps there at kinetic energies
// below 1e-12 of its scale, the gradient measure between 1e-2 and 0.5).
bool DynamicsRun::settled_in_stable_basin(bool at_rest) {
  const double fall = options.endgame.rest_check_fall;
  if (!endgame_on || !second_order || !at_rest || !(fall > 0.0) ||
      !(report.gradient_measure < rest_check_below))
    return false;
  if (is_positive_definite(estimator, objective.hessian())) {
    rest_check_below = report.gradient_measure / options.endgame.growth;
    return true;
  }
  rest_check_below = fall * report.gradient_measure;
  return false;
}

// Ends a blend that is over; then, when the unknowns moved far enough
// (DampingRefreshOptions::distance), stiffness-proportional damping from
// the Hessian here, blended in over refresh.blend_steps steps of length h.
void DynamicsRun::refresh_by_distance(double h) {
  const bool blending = system.update_blend(t);
  if (!blending && options.refresh.distance > 0.0 &&
      options.damping.model == DampingModel::Rayleigh &&
      (y.head(n) - refreshed_at).cwiseQuotient(scales).cwiseAbs().maxCoeff() >
          options.refresh.distance) {
    refreshed_at = y.head(n);
    system.blend_damping(refreshed_damping(), t, options.refresh.blend_steps * h);
    ++result.refreshes;
  }
}

// Rebases the objective when the unknowns moved far enough (or by count,
// RebaseOptions), and restarts IDA from the re-expressed state when the
// rebase, or a damping refresh with it, changed anything.
void DynamicsRun::rebase_if_due(double h) {
  const bool far = options.rebase.distance > 0.0 &&
                   ((y.head(n) - rebased_at).cwiseQuotient(scales).cwiseAbs().maxCoeff() >
                    options.rebase.distance);
  const bool due =
      options.rebase.interval > 0 && result.iterations - last_rebase >= options.rebase.interval;
  if (!(far || due)) return;
  last_rebase = result.iterations;
  Eigen::VectorXd v = second_order ? Eigen::VectorXd(y.tail(n)) : Eigen::VectorXd();
  objective.rebase(second_order ? &v : nullptr);
  evaluator.sync();
  ++result.rebases;
  const Eigen::VectorXd before = y;
  y.head(n) = objective.get();
  if (second_order) y.tail(n) = v;
  rebased_at = y.head(n);
  refreshed_at = y.head(n);
  weights = objective.gradient_weights();
  last_good = y;
  last_total = report.energy + kinetic(y);  // v re-expressed
  bool restart = !(y == before);
  if (options.refresh.at_rebase > 0 && options.damping.model == DampingModel::Rayleigh) {
    system.set_damping(refreshed_damping());
    restart = true;
  } else if (options.refresh.at_rebase > 0 && choice.unstable) {
    choice = choose_damping(options, estimator, objective.hessian(), mass);
    system.set_damping(choice.damping);
    restart = true;
  }
  if (!restart) return;  // nothing was re-expressed: no restart needed
  restart_at(t, options.rebase.restart_step > 0 ? h * options.rebase.restart_step : 0.0);
}

// Rayleigh damping from the Hessian at the current configuration.
Damping DynamicsRun::refreshed_damping() {
  const Eigen::SparseMatrix<double>& H = objective.hessian();
  if (options.refresh.at_rebase >= 2) {
    const ModeEstimate warm = choice.modes;
    choice = choose_damping(options, estimator, H, mass, &warm);
    result.damping = choice.c;
    return choice.damping;
  }
  Damping d = system.damping();
  const double b = d.stiffness_coefficient;
  if (!(b > 0.0)) return d;
  const Eigen::VectorXd shift = (d.mass_coefficient / b) * mass;
  d.stiffness = H;
  if (estimator.factorize(H, &shift) != FactorizationStatus::PositiveDefinite) {
    const ShiftedFactorization f = factorize_with_shift(estimator, H, mass, options.shift);
    d.mass_coefficient = b * f.shift;
  }
  return d;
}

// Restarts IDA at (time, y), the objective being at y's q, with
// consistent derivatives and first step h_first (0: first_step's).
void DynamicsRun::restart_at(double time, double h_first) {
  as_eigen(integrator->y.get()) = y;
  as_eigen(integrator->yp.get()) = system.consistent_derivatives(y, time);
  accumulate_stats();
  void* m = integrator->ida.get();
  check_sundials(IDAReInit(m, time, integrator->y.get(), integrator->yp.get()), "IDAReInit");
  as_eigen(integrator->atol.get()) = absolute_tolerances();
  check_sundials(
      IDASVtolerances(m, options.error_control.relative_tolerance, integrator->atol.get()),
      "IDASVtolerances");
  if (!(h_first > 0.0))
    h_first = first_step(y, as_eigen(integrator->yp.get()), as_eigen(integrator->atol.get()),
                         options.error_control.relative_tolerance, n, q_only);
  check_sundials(IDASetInitStep(m, h_first), "IDASetInitStep");
}

// Rejects the step of length h just taken: IDA restarts from last_good
// with half of it (at order 1, backward Euler, as every restart).
// Returns false, the run finished, when that step would be stagnant.
bool DynamicsRun::retry_shorter(double h, const std::string& why) {
  ++result.rejected_steps;
  y = last_good;
  t = last_good_t;
  if (0.5 * h <= kStagnantStepRatio * t) {  // the objective is moved to y after the stepping
    finish(SolveStatus::IntegratorFailed,
           why + " even for steps of " + scientific(0.5 * h) + " at t = " + scientific(t));
    return false;
  }
  if (evaluator.move_to(y.data()) != 0) {
    evaluator.rethrow_if_fatal();
    finish(SolveStatus::IntegratorFailed,
           "the objective rejected an accepted state: " + evaluator.last_message());
    return false;
  }
  restart_at(t, 0.5 * h);
  return true;
}

// The end game from the last accepted state (EndgameOptions). Returns true
// when it did not converge and the dynamics resume; false when the run is
// finished.
bool DynamicsRun::play_endgame() {
  const int max_iterations = static_cast<int>(
      std::min<long>(options.endgame.iterations,
                     std::max<long>(1, options.stopping.max_steps - result.iterations)));
  if (second_order) y.tail(n).setZero();  // the infinite step ends at rest
  const NewtonResult polished =
      run_endgame(objective, options, max_iterations, callbacks, result.iterations, report);
  result.iterations += polished.iterations;
  result.endgame_steps += polished.iterations;
  extra_factorizations += polished.factorizations;
  evaluator.sync();
  y.head(n) = objective.get();
  weights = objective.gradient_weights();
  if (polished.status == SolveStatus::IterationLimit &&
      result.iterations < options.stopping.max_steps && options.endgame.growth > 1.0) {
    // Handed over too early (far from the equilibrium, in a region
    // where H happens to be positive definite): the dynamics go on at
    // rest from where the end game stopped, its energy lower than at
    // the hand-over (the line search only lowers it).
    ++result.endgame_fallbacks;
    endgame = false;
    endgame_backoff *= options.endgame.growth;
    last_good = y;
    last_good_t = t;
    last_total = polished.energy;
    rebased_at = y.head(n);
    refreshed_at = y.head(n);
    restart_at(t, 0.0);
    return true;
  }
  if (polished.converged()) endgame_stable = polished.stable;
  finish(endgame_status(polished), endgame_reason(polished));
  return false;
}

void DynamicsRun::finish(SolveStatus status, std::string reason) {
  result.status = status;
  result.reason = std::move(reason);
}

// The result at the objective's final state.
DynamicsResult DynamicsRun::final_result() {
  result.time = report.time;
  result.energy = objective.energy();
  result.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
  result.kinetic_energy = kinetic(y);
  // A converged end game tested this state's exact Hessian already.
  if (result.status != SolveStatus::NonFinite)
    result.stable =
        endgame_stable ? *endgame_stable : is_positive_definite(estimator, objective.hessian());
  result.factorizations = estimator.stats().factorizations +
                          system.cholesky().stats().factorizations + extra_factorizations;
  result.seconds = seconds_since(start);
  return result;
}

// v'Mv / 2 of a state (0 in the first-order form).
double DynamicsRun::kinetic(const Eigen::VectorXd& state) const {
  return second_order ? 0.5 * state.tail(n).dot(mass.cwiseProduct(state.tail(n))) : 0.0;
}

// IDA's absolute tolerances: for q in units of unknown_scales, for v those
// times the slowest rate.
Eigen::VectorXd DynamicsRun::absolute_tolerances() const {
  Eigen::VectorXd atol(system.size());
  atol.head(n) = options.error_control.absolute_tolerance * scales;
  if (second_order) atol.tail(n) = atol.head(n) * system.damping().rate;
  return atol;
}

// Adds IDA's counters to the result (IDAReInit resets them).
void DynamicsRun::accumulate_stats() {
  long value = 0;
  void* m = integrator->ida.get();
  IDAGetNumResEvals(m, &value);
  result.residual_evaluations += value;
  IDAGetNumErrTestFails(m, &value);
  result.error_test_failures += value;
  IDAGetNumNonlinSolvConvFails(m, &value);
  result.convergence_failures += value;
}

}  // namespace xshell
