#include "integrators/kinetic_damping/kinetic_damping.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/dynamics/mass_and_damping.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"

namespace xshell {

namespace {

constexpr double kTimeStep = 1.0;  // dt: the masses scale with dt^2, so its value is immaterial

// Moves the objective to q and returns E there, or NaN when q is not a valid
// configuration (set() threw std::domain_error; `message` says why).
double energy_at(Objective& objective, const Eigen::VectorXd& q, std::string& message) {
  try {
    objective.set(q);
  } catch (const std::domain_error& e) {
    message = e.what();
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double e = objective.energy();
  if (!std::isfinite(e)) message = "non-finite energy";
  return e;
}

// Peak time tau* in [-1/2, 1/2] around t_{n-1/2} from the parabola through
// the kinetic energies at tau = -1, 0, 1 (see PeakLocation::Parabola).
double parabola_peak(double before, double peak, double after) {
  const double curvature = before - 2.0 * peak + after;
  if (!(curvature < 0.0)) return 0.0;
  return std::clamp((before - after) / (2.0 * curvature), -0.5, 0.5);
}

// One run of solve_kinetic_damping: the accepted state, the leapfrog's
// state, and the iteration's steps as methods (the leapfrog step, the
// reset at a kinetic-energy peak, the energy-rise check, the rebase, the
// rejection of a step, the stop test). Like NewtonSolver::Impl, it names
// its members as a procedure names its variables.
class KineticDampingRun {
 public:
  // The objective must have free unknowns (size() > 0); started: when the
  // run began, for result.seconds.
  KineticDampingRun(Objective& target, const KineticDampingOptions& run_options,
                    const KineticDampingCallbacks& run_callbacks, Clock::time_point started);

  // Relaxes until convergence or failure; call once.
  KineticDampingResult solve();

 private:
  enum class StepOutcome { Accepted, Rejected, Finished };

  bool iterate();
  bool stopped_by_watches(long iteration);
  StepOutcome take_step(long iteration, const Eigen::VectorXd& next_velocity,
                        const Eigen::VectorXd& step, double next_energy, std::string& failure);
  void reset_at_peak(double ke, Eigen::VectorXd& next_q, double& accepted_energy);
  bool energy_rose(long iteration, double accepted_energy);
  bool rebase_if_due(long iteration, bool peak, bool rise, double accepted_energy);
  bool reject(const std::string& failure, Clock::time_point iteration_start);
  void refresh_masses(long iteration);
  void come_to_rest();
  void finish(SolveStatus status, std::string reason);
  KineticDampingResult final_result();

  Objective& objective;                      // moved along the run; left at the accepted state
  const KineticDampingOptions& options;      // as given
  const KineticDampingCallbacks& callbacks;  // as given
  const Clock::time_point start;             // when the run began
  const double dt = kTimeStep;               // the leapfrog's time step
  KineticDampingResult result;               // filled along the run
  // The accepted state: q (current parametrization), its energy and gradient.
  Eigen::VectorXd q;
  double energy = 0.0;
  Eigen::VectorXd gradient;
  Eigen::VectorXd weights;      // gradient weights (change at rebases)
  double energy0 = 0.0;         // E at the start
  KineticDampingReport report;  // of the current iteration (or the start)
  // Leapfrog state: v = v_{n-1/2} (zero at rest), the last two kinetic
  // energy samples since the last reset, and the energy at that reset.
  Eigen::VectorXd velocity;
  bool at_rest = true;
  double ke_last = 0.0, ke_before = 0.0;
  int samples = 0;  // kinetic-energy samples since the last reset
  double energy_at_reset = 0.0;
  double safety = 0.0;    // the masses' safety factor (grows with mass_growth)
  Eigen::VectorXd mass;   // the fictitious masses, diagonal
  long last_refresh = 0;  // iteration of the last mass refresh
  long last_rise = std::numeric_limits<long>::min() / 2;  // iteration of the last energy rise
  long since_rebase = 0;                                  // iterations since the last rebase
  int rejected_since_peak = 0;                  // rejected steps since the last kinetic-energy peak
  std::optional<ProgressWatch> watch;           // windows of progress_watch.hpp (off by default)
  std::optional<KineticDampingWatch> kd_watch;  // divergence and stagnation, from the start
};

KineticDampingRun::KineticDampingRun(Objective& target, const KineticDampingOptions& run_options,
                                     const KineticDampingCallbacks& run_callbacks,
                                     Clock::time_point started)
    : objective(target), options(run_options), callbacks(run_callbacks), start(started) {
  result.mass_safety = options.mass_safety;
  q = objective.get();
  energy = objective.energy();
  gradient = objective.gradient();
  ++result.gradient_evaluations;
  weights = objective.gradient_weights();
  energy0 = energy;
  report.energy = energy;
  report.gradient_measure = weighted_max_norm(weights, gradient);
  if (options.progress.window > 0) watch.emplace(energy, report.gradient_measure, options.progress);
  kd_watch.emplace(energy, report.gradient_measure, options.watch);
  velocity = Eigen::VectorXd::Zero(q.size());
  energy_at_reset = energy;
  safety = options.mass_safety;
}

KineticDampingResult KineticDampingRun::solve() {
  if (callbacks.on_iteration) callbacks.on_iteration(report);
  if (!std::isfinite(energy) || !std::isfinite(report.gradient_measure)) {
    finish(SolveStatus::NonFinite, "energy or gradient not finite at the start");
  } else if (report.gradient_measure <= options.gradient_tolerance) {
    finish(SolveStatus::Converged, "in equilibrium at the start");
  } else {
    refresh_masses(0);
    while (iterate()) {
    }
  }
  return final_result();
}

// One leapfrog iteration and its report. Returns false when the run is
// finished (result.status set).
bool KineticDampingRun::iterate() {
  if (stop_or_limit(callbacks.stop, result.iterations, options.max_iterations, "iterations",
                    result))
    return false;
  const Clock::time_point iteration_start = Clock::now();
  const long iteration = ++result.iterations;
  report = KineticDampingReport{};
  report.iteration = iteration;

  // The leapfrog step; from rest, Barnes's half step.
  const Eigen::VectorXd acceleration = -gradient.cwiseQuotient(mass);  // M^-1 R_n
  const Eigen::VectorXd next_velocity = at_rest ? Eigen::VectorXd(0.5 * dt * acceleration)
                                                : Eigen::VectorXd(velocity + dt * acceleration);
  const Eigen::VectorXd step = dt * next_velocity;
  report.step_norm = step.cwiseAbs().maxCoeff();
  std::string failure;
  const double next_energy = energy_at(objective, q + step, failure);
  const StepOutcome outcome = std::isfinite(next_energy)
                                  ? take_step(iteration, next_velocity, step, next_energy, failure)
                                  : StepOutcome::Rejected;
  if (outcome == StepOutcome::Finished) return false;
  if (outcome == StepOutcome::Rejected && !reject(failure, iteration_start)) return false;

  report.energy = energy;
  report.kinetic_energy = at_rest ? 0.0 : ke_last;
  report.gradient_measure = weighted_max_norm(weights, gradient);
  report.seconds = seconds_since(iteration_start);
  if (callbacks.on_iteration) callbacks.on_iteration(report);
  const double energy_scale = std::max(std::abs(energy0 - energy), std::abs(energy));
  if (report.gradient_measure <= options.gradient_tolerance &&
      report.kinetic_energy <= options.kinetic_tolerance * energy_scale) {
    finish(SolveStatus::Converged, "gradient and kinetic energy below tolerance");
    return false;
  }
  return !stopped_by_watches(iteration);
}

// Whether a watch found the run diverging or stagnating (then finished).
bool KineticDampingRun::stopped_by_watches(long iteration) {
  const KineticDampingProgress verdict =
      kd_watch->observe(iteration, energy, report.gradient_measure, report.kinetic_energy);
  if (verdict != KineticDampingProgress::Continuing) {
    finish(verdict == KineticDampingProgress::Diverging ? SolveStatus::Diverged
                                                        : SolveStatus::IntegratorFailed,
           kd_watch->reason());
    return true;
  }
  const Progress progress =
      watch ? watch->observe(energy, report.gradient_measure, report.kinetic_energy)
            : Progress::Continuing;
  if (progress != Progress::Continuing) {
    finish(progress == Progress::Diverging ? SolveStatus::Diverged : SolveStatus::IntegratorFailed,
           watch->reason());
    return true;
  }
  return false;
}

// The leapfrog step to q + step (energy next_energy, finite) is taken:
// kinetic damping at a peak, the energy-rise check, the rebase, and the
// gradient at the new state. Rejected (failure says why) when that
// gradient is not finite and the state can go back; Finished when it
// cannot.
KineticDampingRun::StepOutcome KineticDampingRun::take_step(long iteration,
                                                            const Eigen::VectorXd& next_velocity,
                                                            const Eigen::VectorXd& step,
                                                            double next_energy,
                                                            std::string& failure) {
  const double ke = 0.5 * next_velocity.dot(mass.cwiseProduct(next_velocity));
  Eigen::VectorXd next_q = q + step;
  double accepted_energy = next_energy;
  const bool peak = ke < ke_last;
  if (peak) {
    reset_at_peak(ke, next_q, accepted_energy);
  } else {
    velocity = next_velocity;
    at_rest = false;
    ke_before = ke_last;
    ke_last = ke;
    ++samples;
  }
  const bool rise = energy_rose(iteration, accepted_energy);
  const bool rebased = rebase_if_due(iteration, peak, rise, accepted_energy);
  if (rebased) {
    since_rebase = 0;
    ++result.rebases;
    next_q = objective.get();
    weights = objective.gradient_weights();
  }
  Eigen::VectorXd next_gradient = objective.gradient();
  ++result.gradient_evaluations;
  if (next_gradient.allFinite()) {
    q = std::move(next_q);
    energy = accepted_energy;
    gradient = std::move(next_gradient);
    return StepOutcome::Accepted;
  }
  if (rebased) {  // q is expressed in the old unknowns: no way back
    energy = accepted_energy;
    gradient = std::move(next_gradient);
    finish(SolveStatus::NonFinite,
           "non-finite gradient after iteration " + std::to_string(iteration));
    return StepOutcome::Finished;
  }
  failure = "non-finite gradient";
  return StepOutcome::Rejected;
}

// A kinetic-energy peak was passed (ke, the new sample, fell below the
// last): back to the peak on the segment q_{n-1} -> q_n (velocity
// v_{n-1/2}), at rest. next_q and accepted_energy become the peak's.
void KineticDampingRun::reset_at_peak(double ke, Eigen::VectorXd& next_q, double& accepted_energy) {
  const double tau = options.peak == PeakLocation::Parabola && samples >= 2
                         ? parabola_peak(ke_before, ke_last, ke)
                         : 0.0;
  const Eigen::VectorXd peak_q = q - ((0.5 - tau) * dt) * velocity;
  std::string ignored;
  const double peak_energy = energy_at(objective, peak_q, ignored);
  if (std::isfinite(peak_energy)) {
    next_q = peak_q;
    accepted_energy = peak_energy;
  } else {  // cannot happen on a convex valid set; stay at q_{n+1}
    objective.set(next_q);
  }
  come_to_rest();
  ++result.resets;
  report.reset = true;
  rejected_since_peak = 0;
}

// The stable leapfrog from rest never raises a quadratic energy above its
// starting value: a rise means the masses are too light here. On a rise
// the run comes to rest, and a second rise soon after raises the safety.
bool KineticDampingRun::energy_rose(long iteration, double accepted_energy) {
  const double margin = options.energy_rise_tolerance *
                        std::max(std::abs(energy_at_reset), energy0 - energy_at_reset);
  const bool rise = accepted_energy > energy_at_reset + margin;
  if (rise) {
    come_to_rest();
    ++result.energy_rises;
    report.energy_rise = true;
    if (iteration - last_rise < options.mass_refresh_interval) safety *= options.mass_growth;
    last_rise = iteration;
  }
  return rise;
}

// Rebases the objective at a reset (peak or rise), with new masses when
// due, or after rebase_interval iterations without one (velocities
// transformed). Returns whether it rebased.
bool KineticDampingRun::rebase_if_due(long iteration, bool peak, bool rise,
                                      double accepted_energy) {
  if (peak || rise) {
    // v = 0: the rebase and the new masses cost no velocity transform.
    objective.rebase(nullptr);
    if (rise || iteration - last_refresh >= options.mass_refresh_interval) {
      refresh_masses(iteration);
      report.mass_refreshed = true;
    }
    energy_at_reset = accepted_energy;
    return true;
  }
  if (++since_rebase >= std::max(options.rebase_interval, 1L)) {
    objective.rebase(&velocity);
    ke_last = 0.5 * velocity.dot(mass.cwiseProduct(velocity));
    return true;
  }
  return false;
}

// Back to the last accepted state, at rest, with heavier masses. Returns
// false, the run finished, after too many rejections without a peak.
bool KineticDampingRun::reject(const std::string& failure, Clock::time_point iteration_start) {
  objective.set(q);
  come_to_rest();
  energy_at_reset = energy;
  safety *= options.mass_growth;
  mass *= options.mass_growth;
  ++result.rejected_steps;
  report.rejected = true;
  if (++rejected_since_peak > options.max_rejected_steps) {
    const bool invalid = failure.rfind("non-finite", 0) != 0;
    finish(invalid ? SolveStatus::InvalidConfiguration : SolveStatus::NonFinite,
           std::to_string(rejected_since_peak) +
               " steps rejected without a kinetic-energy peak between: " + failure);
    report.energy = energy;
    report.gradient_measure = weighted_max_norm(weights, gradient);
    report.seconds = seconds_since(iteration_start);
    if (callbacks.on_iteration) callbacks.on_iteration(report);
    return false;
  }
  return true;
}

// m_i = safety (dt^2/4) sum_j |K_ij| (Gerschgorin; fictitious_mass floors empty rows).
void KineticDampingRun::refresh_masses(long iteration) {
  const Eigen::SparseMatrix<double>& H = objective.hessian();
  mass = (0.25 * safety * dt * dt) *
         (options.mass_bound == MassBound::RowSum ? fictitious_mass(H) : scaled_fictitious_mass(H));
  last_refresh = iteration;
  ++result.mass_refreshes;
}

void KineticDampingRun::come_to_rest() {
  velocity.setZero();
  at_rest = true;
  ke_last = ke_before = 0.0;
  samples = 0;
}

void KineticDampingRun::finish(SolveStatus status, std::string reason) {
  result.status = status;
  result.reason = std::move(reason);
}

// The result at the accepted state, with the stability check.
KineticDampingResult KineticDampingRun::final_result() {
  result.mass_safety = safety;
  result.energy = energy;
  result.gradient_measure = weighted_max_norm(weights, gradient);
  result.kinetic_energy = at_rest ? 0.0 : ke_last;
  if (result.status != SolveStatus::NonFinite) {
    CholeskySolver cholesky;
    result.stable = is_positive_definite(cholesky, objective.hessian());
    result.factorizations = cholesky.stats().factorizations;
  }
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace

Eigen::VectorXd scaled_fictitious_mass(const Eigen::SparseMatrix<double>& H) {
  const Eigen::Index n = H.rows();
  Eigen::VectorXd d = H.diagonal().cwiseAbs();
  const double largest = n > 0 ? d.maxCoeff() : 0.0;
  if (!(largest > 0.0) || !std::isfinite(largest)) return fictitious_mass(H);
  d = d.cwiseMax(1e-12 * largest);
  const Eigen::VectorXd root = d.cwiseSqrt();
  Eigen::VectorXd m = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < H.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, j); it; ++it)
      m[it.row()] += std::abs(it.value()) * root[it.row()] / root[j];
  return m.cwiseMax(d);
}

KineticDampingResult solve_kinetic_damping(Objective& objective,
                                           const KineticDampingOptions& options,
                                           const KineticDampingCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  if (objective.size() == 0) {
    KineticDampingResult result;
    result.mass_safety = options.mass_safety;
    set_no_unknowns(objective.energy(), result);
    return result;
  }
  KineticDampingRun run(objective, options, callbacks, start);
  return run.solve();
}

}  // namespace xshell
