// Statics by damped dynamics with IDA: integrate
//   M q'' + C q' + grad E(q) = 0   (second order)
// or the overdamped C q' + grad E(q) = 0 (first order) until the motion has
// died out, with IDA's adaptive BDF steps (which grow as the motion decays,
// approaching Newton steps: pseudo-transient continuation, Kelley & Keyes
// 1998). Damped dynamics only lowers E + kinetic energy, so it settles in
// stable minima where Newton may stop at a saddle; from an exactly
// symmetric start it can still stay on a symmetric saddle.
//
// Start (second order, DynamicsStartOptions): by default on the slow
// manifold, v_0 = -(C + M/T)^-1 grad E with T one time constant
// (start.time): for the overdamped modes (c >> m/T) that is the overdamped
// velocity -C^-1 grad E, at which M v' = -(C v + grad E) vanishes, so the
// initial layer in which a start from rest accelerates them to it does not
// occur; weakly damped modes (zero modes of free ends) get only the velocity
// -T M^-1 grad E they would reach in a time T. IDA's first step is then
// start.step_factor (16) times the estimate, which is sized for an initial
// layer. From an indefinite Hessian (a saddle start) the start is at rest:
// the slow manifold does not attract along unstable modes. E + K starts at
// E_0 + K_0 and still only decreases. (Measurements: docs/tuning.md.)
//
// Damping (DampingModel): by default Rayleigh, C = b (H_0 + mu M) with H_0
// the Hessian at the start: every mode of H_0 stiffer than the slowest is
// overdamped and decays at about the slowest mode's rate, so the stiff
// modes cost no small steps (mass-proportional damping C = c M leaves them
// ringing). b and mu come from the lowest eigenvalues (inverse iteration,
// mass_and_damping.hpp); near a saddle mu makes H_0 + mu M positive
// definite. The alternative C = c M is kept (DampingModel::MassProportional).
//
// Layout and linear algebra: ida_system.hpp (Schur complement onto
// the n x n symmetric K = H + (c_j^2 + a c_j) M + b c_j S, factorized by
// CHOLMOD).
//
// Stepping: IDA_ONE_STEP; after every step the objective is moved to the
// step's q and the stop criterion is tested:
//   gradient measure <= stopping.gradient_tolerance  and
//   kinetic energy <= stopping.kinetic_tolerance * max(|E_0 - E|, |E|)
// (second order; the first-order form has no kinetic energy). When the
// unknowns have moved far enough (rebase.distance), objective.rebase(&v)
// re-expresses them and IDA restarts (IDAReInit) from the transformed state
// with consistent derivatives (q' = v, v' = -M^-1 (C v + grad E)); when the
// rebase changed neither q nor v, IDA simply continues (a restart drops IDA
// back to order 1). The end game (EndgameOptions) takes the last steps at
// infinite length, i.e. as Newton steps with the energy line search: once
// the steps are many time constants long in a stable basin, or the motion
// is at rest near an equilibrium, or (second order) at rest where H is
// positive definite.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "integrators/common/objective.hpp"
#include "integrators/common/progress_watch.hpp"
#include "integrators/common/solve_result.hpp"
#include "integrators/dynamics/ida_system.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"
#include "integrators/stability/saddle_escape.hpp"

namespace xshell {

enum class MassModel {
  Physical,    // objective.mass()
  Fictitious,  // row sums of |H| at the start (dynamic relaxation)
};

enum class DampingModel {
  MassProportional,  // C = c M
  Rayleigh,          // C = a M + b (H_r + s M), see mass_and_damping.hpp
};

// Initial velocity of the second-order form (the first-order form has none).
enum class DynamicsStart {
  Rest,          // v = 0
  SlowManifold,  // v = -(C + M/T)^-1 grad E (see above); at rest from an indefinite Hessian
};

// The options of solve_dynamics, in groups, each setting with what it does
// and its unit. The defaults are those the tests, the samples and the
// benchmark were tuned with; docs/tuning.md has the measurements behind
// them. A "time constant" is 1 / rate of the slowest damped mode; "units of
// unknown_scales" are radians for angles and the length scale of the
// gradient weights for positions.

// Where the motion starts (second order; the first-order form has no v).
struct DynamicsStartOptions {
  // v_0: at rest, or on the slow manifold (see above).
  DynamicsStart velocity = DynamicsStart::SlowManifold;
  // SlowManifold: T in v_0 = -(C + M/T)^-1 grad E, in time constants; 0: v_0 = -C^-1 grad E.
  double time = 1.0;
  // SlowManifold: the first step is this times first_step's estimate (<= 1: the estimate).
  double step_factor = 16.0;
  // At rest (asked for, or the slow manifold refused): the first step is this times the estimate
  // (<= 1: the estimate), which is sized for velocities the error test does not see. Relaxations
  // from flat (xshell_bench --solvers, 8 edges per segment): 10 saves manta_ray 3 of 30 steps,
  // darth_vader 16 of 53, hourglass 2 of 29, the largest design 7 of 131.
  double rest_step_factor = 10.0;
  // SlowManifold: v_0 is scaled down to move no unknown further in one time constant (units of
  // unknown_scales); a (nearly) zero mode of H_0 makes it large.
  double reach = 0.3;
  // First step (time), overriding the estimates, in either form; 0: estimated.
  double initial_step = 0.0;
};

// The damping C, chosen from the lowest modes of (H_0, M) (damping_choice.hpp).
struct DampingOptions {
  // C = c M, or Rayleigh C = b (H_0 + mu M).
  DampingModel model = DampingModel::Rayleigh;
  // c of C = c M; Rayleigh: critical damping at eigenvalue c^2 / 4 (1 / time); <= 0: automatic.
  double coefficient = 0.0;
  // Inverse iterations per estimated eigenvalue (at most: an iteration that converged stops).
  int iterations = 20;
  // Eigenvalues below mode_floor trace(H) / trace(M) count as zero (dimensionless).
  double mode_floor = 1e-12;
  // Rayleigh near a saddle (second order): mu >= this times -lambda_min, so H + mu M > 0.
  double unstable_margin = 1.1;
  // Rayleigh: mu >= this times the lowest stable eigenvalue, so that zero modes are damped.
  double zero_mode_fraction = 0.3;
};

// Rayleigh damping recomputed from the current Hessian during the run (off by default: each
// refresh costs a factorization).
struct DampingRefreshOptions {
  // At every rebase: 0 never; 1 S = the current H, b kept (mass-proportional damping after an
  // unstable start: c chosen anew); >= 2 b and mu chosen anew too, in every refresh.
  int at_rebase = 0;
  // Also once an unknown moved this far since the last refresh (units of unknown_scales); 0: never.
  double distance = 0.0;
  // A refresh by distance is blended in over this many steps of the current length.
  double blend_steps = 5.0;
};

// When the run ends, as for the other solvers.
struct DynamicsStoppingOptions {
  // Converged once the gradient measure (as NewtonOptions, dimensionless) is at most this...
  double gradient_tolerance = 2e-8;
  // ... and the kinetic energy at most this times max(|E_0 - E|, |E|).
  double kinetic_tolerance = 1e-12;
  // Accepted steps, the end game's Newton steps included.
  long max_steps = 100000;
  // Stops a run that diverges or stagnates (no progress beyond round-off)
  // over a window of steps: Diverged or IntegratorFailed.
  ProgressWatchOptions progress = {1000, 1e-12, 1};
};

// Rebases (objective.rebase: source-frame updates, omega folds); each restarts IDA at order 1.
struct RebaseOptions {
  // Once an unknown moved this far since the last rebase (units of unknown_scales); 0: never so.
  double distance = 0.3;
  // Also every this many steps; 0: never by count.
  int interval = 0;
  // First step after the restart, as a multiple of the last step; 0: first_step's estimate.
  // (Measurements: docs/tuning.md.)
  double restart_step = 2.0;
};

// IDA's local error control. Statics needs a decreasing E + K and the right basin, not an
// accurate trajectory.
struct ErrorControlOptions {
  // IDA's rtol (dimensionless).
  double relative_tolerance = 2e-2;
  // IDA's atol for q, in units of unknown_scales; for v, that times the slowest rate.
  double absolute_tolerance = 1e-4;
  // atol per unknown times unknown_scales; false: one atol for every unknown.
  bool scaled_tolerances = true;
  // Velocities out of IDA's error test (IDASetId, IDASetSuppressAlg); the first step is then
  // sized from the motion of q alone (first_step).
  bool suppress_velocity = true;
};

// The steps IDA may take.
struct StepControlOptions {
  // Largest BDF order (at most 2 in the first-order form).
  int max_order = 2;
  // Largest growth of the step from one step to the next (factor; IDA's default is 2).
  double eta_max = 5.0;
  // A step after which E + K rose by more than this times its drop so far is taken again, half
  // as long, from a restart at order 1 (backward Euler); 0: no guard.
  double dissipation_guard = 1e-7;
  // After K failed to factorize, hold the step below the failed one for a while (ida_step_cap.hpp).
  bool cap_indefinite = true;
};

// The end game: the last steps at infinite length, i.e. Newton steps with the energy line search
// (newton.hpp), which only lowers the energy.
struct EndgameOptions {
  // Begins once IDA's step is this many time constants and H is positive definite; 0: no end game.
  // 1e2 rather than 1e3: darth_vader from flat 34 -> 29 steps (docs/tuning.md).
  double step_length = 1e2;
  // Or once at rest with the gradient measure within this factor of the tolerance; 0: not so.
  double gradient_factor = 100.0;
  // Or (second order) once at rest where H is positive definite, whatever the gradient: the
  // motion has died out in a stable basin. A check that finds H indefinite is made again only
  // once the gradient measure has fallen below this fraction of its value there; 0: no such
  // end game. Relaxations from flat (xshell_bench --solvers): scary_face 21 -> 17 steps.
  double rest_check_fall = 0.1;
  // Newton iterations of one end game.
  int iterations = 30;
  // An end game that does not converge: the dynamics resume at rest, and both triggers wait this
  // factor longer (step, or smaller gradient); <= 1: the run fails instead.
  double growth = 4.0;
};

struct DynamicsOptions {
  // Second order M q'' + C q' + grad E = 0, or first order C q' + grad E = 0.
  DynamicsForm form = DynamicsForm::SecondOrder;
  // M: the objective's, or fictitious (row sums of |H_0|).
  MassModel mass = MassModel::Physical;
  DynamicsStartOptions start;
  DampingOptions damping;
  DampingRefreshOptions refresh;
  DynamicsStoppingOptions stopping;
  RebaseOptions rebase;
  ErrorControlOptions error_control;
  StepControlOptions steps;
  EndgameOptions endgame;
  // Shifted factorizations of an indefinite Hessian: damping estimate, refresh, end game.
  ShiftOptions shift;
  // A converged state that is a saddle (round-off kept the motion on it, as
  // from a symmetric start): left along its lowest mode, as Newton does,
  // and integrated on from rest (enabled by default).
  SaddleEscapeOptions escape;
};

// One per accepted step, and one for the initial state (step 0).
struct DynamicsReport {
  long step = 0;
  double time = 0.0;            // simulated time
  double step_size = 0.0;       // of the last step
  double energy = 0.0;          // E(q)
  double kinetic_energy = 0.0;  // v'Mv/2 (0 in the first-order form)
  double gradient_measure = 0.0;
  int order = 0;  // BDF order of the last step
};

struct DynamicsCallbacks {
  std::function<void(const DynamicsReport&)> on_step;  // optional
  const std::atomic<bool>* stop = nullptr;             // optional; checked before each step
};

// The common result (solve_result.hpp) and what the dynamics adds.
// iterations counts the accepted time steps, the end game's included;
// LinearSolverFailed: K could not be factorized, or gave no finite
// correction, even for short steps; IntegratorFailed: other IDA failures
// (error test, convergence, steps stagnating below 1e-12 t), or invalid
// configurations. factorizations include the damping estimate's.
struct DynamicsResult : SolveResult {
  double time = 0.0;  // simulated time at the end
  double kinetic_energy = 0.0;
  double damping = 0.0;            // c (or a) used
  double stiffness_damping = 0.0;  // b used (0 for mass-proportional damping)
  long residual_evaluations = 0;
  long error_test_failures = 0;
  long convergence_failures = 0;
  long rebases = 0;
  long refreshes = 0;          // damping refreshes
  long endgame_steps = 0;      // steps of infinite length (Newton) at the end
  long endgame_fallbacks = 0;  // end games that did not converge, after which the dynamics resumed
  long rejected_steps = 0;  // steps retried shorter: by dissipation_guard, or ending in an invalid
                            // configuration (not counted in iterations)
};

// Integrates from the objective's current configuration, at rest or on the
// slow manifold (options.start; the step-0 report carries K_0). On failure
// the objective is left at the last accepted step.
DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options = {},
                              const DynamicsCallbacks& callbacks = {});

}  // namespace xshell
