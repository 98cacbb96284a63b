// Statics by damped dynamics with IDA: integrate
//   M q'' + C q' + grad E(q) = 0   (second order)
// or the overdamped C q' + grad E(q) = 0 (first order) until the motion has
// died out, with IDA's adaptive BDF steps (which grow as the motion decays,
// approaching Newton steps: pseudo-transient continuation, Kelley & Keyes
// 1998). Damped dynamics only lowers E + kinetic energy, so it settles in
// stable minima where Newton may stop at a saddle; from an exactly
// symmetric start it can still stay on a symmetric saddle.
//
// Start (second order, DynamicsStart): by default on the slow manifold,
// v_0 = -(C + M/T)^-1 grad E with T one time constant (start_time): for
// the overdamped modes (c >> m/T) that is the overdamped velocity
// -C^-1 grad E, at which M v' = -(C v + grad E) vanishes, so the initial
// layer in which a start from rest accelerates them to it does not occur;
// weakly damped modes (zero modes of free ends) get only the velocity
// -T M^-1 grad E they would reach in a time T. IDA's first step is then start_step (16) times the
// estimate, which is sized for an initial layer. From an indefinite Hessian
// (a saddle start) the start is at rest: the slow manifold does not attract
// along unstable modes, and starting there made the tee and single-X
// linkages 2-25% slower. Measured on the test linkages with stable starts:
// 6-30% fewer steps than from rest on four of six (saddle sample 103 -> 85,
// sphere_open 27 -> 19, samples/grid 42 -> 33, curved grid 195 -> 184), as
// many on the other two. E + K starts at E_0 + K_0 and still only
// decreases.
//
// Damping (DampingModel): by default Rayleigh, C = b (H_0 + mu M) with H_0
// the Hessian at the start: every mode of H_0 stiffer than the slowest is
// overdamped and decays at about the slowest mode's rate, so the stiff
// modes cost no small steps (mass-proportional damping C = c M leaves them
// ringing). b and mu come from the lowest eigenvalues (inverse iteration,
// mass_and_damping.hpp); near a saddle mu makes H_0 + mu M positive
// definite. The alternative C = c M is kept (DampingModel::MassProportional).
//
// Layout and linear algebra: dynamics_system.hpp (Schur complement onto
// the n x n symmetric K = H + (c_j^2 + a c_j) M + b c_j S, factorized by
// CHOLMOD).
//
// Stepping: IDA_ONE_STEP; after every step the objective is moved to the
// step's q and the stop criterion is tested:
//   gradient measure <= gradient_tolerance  and
//   kinetic energy <= kinetic_tolerance * max(|E_0 - E|, |E|)
// (second order; the first-order form has no kinetic energy). When the
// unknowns have moved far enough (rebase_distance), objective.rebase(&v)
// re-expresses them and IDA restarts (IDAReInit) from the transformed state
// with consistent derivatives (q' = v, v' = -M^-1 (C v + grad E)); when the
// rebase changed neither q nor v, IDA simply continues (a restart drops IDA
// back to order 1). The end game (endgame_steps) takes the last steps at
// infinite length, i.e. as Newton steps with the energy line search.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "integrators/common/objective.hpp"
#include "integrators/common/solve_result.hpp"
#include "integrators/dynamics/ida_system.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"

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

struct DynamicsOptions {
  DynamicsForm form = DynamicsForm::SecondOrder;
  DynamicsStart start = DynamicsStart::SlowManifold;
  // SlowManifold: v = -(C + M / T)^-1 grad E with T = start_time time
  // constants (1 / rate of the slowest damped mode); 0: v = -C^-1 grad E
  // exactly (v' = 0 at the start). 0.3 and 0 were no better than 1 on the
  // test linkages.
  double start_time = 1.0;
  // SlowManifold: the first step is start_step times the estimate of
  // first_step below (<= 1: the estimate; initial_step > 0 overrides both).
  // 16 skips four of IDA's step doublings: 2-23% fewer steps than 1 on the
  // stable test linkages (saddle sample 89 -> 85, sphere_open 26 -> 20);
  // 100 and 1000 were no better overall.
  double start_step = 16.0;
  // SlowManifold: the start velocity moves no unknown more than start_reach
  // (in units of unknown_scales, as rebase_distance) in one time constant;
  // a larger one, which a (nearly) zero mode of the starting Hessian gives,
  // is scaled down.
  double start_reach = 0.3;
  MassModel mass = MassModel::Physical;
  DampingModel damping_model = DampingModel::Rayleigh;
  // c in C = c M (mass-proportional), a in C = a M + b (H_r + s M) (Rayleigh);
  // <= 0: automatic (mass_and_damping.hpp).
  double damping = 0.0;
  int damping_iterations = 20;       // inverse iterations for lambda_min
  double gradient_tolerance = 2e-8;  // as NewtonOptions
  double kinetic_tolerance = 1e-12;  // relative to the energy scale, see above
  long max_steps = 100000;
  // Rebases (source-frame updates, omega folds: objective.rebase) restart
  // IDA at order 1, so they are made only when the unknowns have moved far
  // enough to need them: when some unknown moved more than rebase_distance
  // (in units of unknown_scales: radians for angles, the length scale of
  // the gradient weights for positions) since the last one, or every
  // rebase_interval steps (0: never by count). Rebasing every 20 steps
  // made the test linkages 3-5x slower than rebasing by distance.
  int rebase_interval = 0;
  double rebase_distance = 0.3;
  // Damping refresh (Rayleigh): every refresh_damping rebases (0: never),
  // or when the unknowns moved more than refresh_distance (0: never), the
  // stiffness part of C is recomputed from the current Hessian and blended
  // in over blend_steps steps. Off by default: the Hessian of the start
  // damps well enough on the test linkages, and each refresh costs a
  // factorization.
  int refresh_damping = 0;
  double refresh_distance = 0.0;
  double blend_steps = 5.0;
  // First step after a restart, as a multiple of the last step (0: IDA's
  // own estimate from the derivatives, which copes with the jump of the
  // damping force that re-expressed unknowns cause).
  double restart_step = 0.0;
  // Near a saddle (Rayleigh, second order): mu = unstable_margin times the
  // most negative eigenvalue, so that H + mu M is positive definite.
  double unstable_margin = 1.1;
  // An (almost) zero mode at the start, such as a joint free to open, is
  // damped by b mu M with mu >= zero_mode_fraction times the lowest stable
  // eigenvalue; without it, such a mode moves without bound at first. 0.3
  // instead of 1e-2 cut the steps of the tee and single-X linkages (free
  // ends) by 32-40% (second order) and 2-18% (first order); 1 was no better.
  double zero_mode_fraction = 0.3;
  // End game: once IDA's step exceeds endgame_steps time constants (1 /
  // rate of the slowest damped mode) and the Hessian is positive definite,
  // the remaining steps are taken with infinite length: backward Euler then
  // is a Newton step, globalized by the energy line search (newton.hpp),
  // which only lowers the energy. 0: never (IDA to the end).
  double endgame_steps = 1e3;
  // The end game's Newton iterations. An end game that does not converge
  // within them was handed over too far from the equilibrium (where H
  // happens to be positive definite): the dynamics resume at rest
  // from its last state, and the next end game waits for steps
  // endgame_growth times longer, or a gradient endgame_growth times
  // smaller (below; 1: no resumption, the run fails).
  int endgame_iterations = 30;
  double endgame_growth = 4.0;
  // The end game also begins, whatever the step length and the Hessian,
  // once the run is at rest (kinetic energy within kinetic_tolerance) with
  // the gradient measure within endgame_gradient_factor times the
  // tolerance: the motion has settled at an equilibrium that the remaining
  // steps only approach. An equilibrium with an (almost) zero or negative
  // mode (the largest design from flat, which Newton too finds unstable)
  // caps the steps, since K is positive definite only for short ones, and
  // the gradient then fell by about 8% per step: 34 of its 65 steps went
  // from 100 times the tolerance to the tolerance. Newton shifts the
  // indefinite Hessian there (newton.hpp). 0: never.
  double endgame_gradient_factor = 100.0;
  // Velocities excluded from IDA's error test (IDASetId, IDASetSuppressAlg):
  // statics needs the path of q, not an accurate v. With velocities in the
  // test, their absolute tolerance (that of q times the slowest rate) holds
  // a start from rest to steps of 1e-8 to 1e-7 time constants, and the
  // designs spent about half of their steps growing out of them: manta_ray
  // (subdivision 8, from flat) took 222 steps with them and 71 without,
  // darth_vader 284 and 105, the single X linkage test 701 and 216.
  // The first step is then sized from the motion of q alone: h =
  // min(0.5 / |v|, 1 / sqrt(|a|)) in the WRMS norm of q's error weights
  // (v h and a h^2 / 2 half the error test's tolerance), a = v'(0).
  bool suppress_velocity = true;
  // Largest BDF order (at most 2 in the first-order form). With velocities
  // out of the error test, orders 3-5 let E + K rise by 5e-4 of its drop
  // on a toy problem of the tests; orders 1-2 stayed within 1e-6 of it.
  int max_order = 2;
  // BDF2 is not dissipative: at the end of the saddle sample's run from
  // rest, it let E + K rise by 4e-6 of its drop over ten steps of constant
  // size, and by 2e-5 in one step of the column buckling from an
  // imperfection. A step after which E + K rose by more than
  // dissipation_guard times its drop so far is rejected: IDA restarts from
  // the state before it with half its length, at order 1 as every restart
  // (backward Euler, which only lowers E + K for short enough steps).
  // Keeping order 1 for the rest of the run instead took 40-50% more steps
  // on that column. 0: no guard.
  double dissipation_guard = 1e-7;
  // After a factorization of IDA's Jacobian failed (not positive definite,
  // near a saddle), hold the step below the failed one for a while
  // (definite_step_cap.hpp) instead of letting IDA grow it into the same
  // failure. The largest design from flat: 159 -> 42 factorizations.
  bool cap_indefinite_steps = true;
  // Largest growth of the step from one step to the next (IDA's default is
  // 2). The step grows from the start's 1e-5 time constants to hundreds of
  // them at the end. With 5, the second-order form took 7% fewer steps and
  // 12% fewer factorizations over the test linkages and the designs
  // (darth_vader 105 -> 88 steps, the column 132 -> 111, hourglass 65 ->
  // 61; curved grid 184 -> 174); the first-order flow 8-40% fewer
  // factorizations on the designs and as many on the test linkages. 3 and
  // 10 did about as well as 5.
  double eta_max = 5.0;
  // Absolute tolerances per unknown scaled by unknown_scales (the
  // gradient weights), so that positions and angles get their own units.
  bool scaled_tolerances = true;
  double mode_floor = 1e-12;  // eigenvalues below mode_floor trace(H)/trace(M) count as zero
  // IDA local error control: rtol, and atol for q (atol for v is atol c/2).
  // Statics needs no accurate trajectory, only a decreasing E + K and the
  // right basin. With Rayleigh damping, rtol 1e-2 takes 20-35% fewer steps
  // than 1e-3 on the samples, and E + K still rises by at most 1e-7 of its
  // drop on the tests (with mass-proportional damping, rtol 1e-2 let it rise
  // by 3e-4 of the drop on the extended Rosenbrock). 2e-2 took 5-25% fewer
  // steps than 1e-2 on the test linkages, the samples and the designs
  // (saddle sample 78 -> 70, single X 225 -> 167, hourglass 61 -> 52; the
  // column 111 -> 115), with as many factorizations; 4e-2 was no better.
  double relative_tolerance = 2e-2;
  // atol in units of unknown_scales: radians for angles, the length scale
  // for positions. rtol |y| is no tolerance for unknowns near zero (twist
  // angles, omega after a fold, coordinates near the origin, such as the
  // heights of a flat linkage), so atol alone sets how accurately IDA
  // follows them. 1e-6 held those to micro-radians and took 1.2-2.7x the
  // steps of 1e-4 (bench, subdivision 8, 2 threads: saddle sample 71 -> 39
  // steps, grid 27 -> 15, manta_ray 58 -> 30, hourglass 52 -> 29, largest
  // 31 -> 22, uniform_linkage 119 -> 87); 3e-4 was about as good, and
  // 1e-3 rejected many steps (E + K rising) on uniform_linkage under
  // gravity. Only hyperboloid_open under gravity, which Newton does not
  // solve either, took more (1649 -> 2572).
  double absolute_tolerance = 1e-4;
  double initial_step = 0.0;  // 0: IDA's estimate
  ShiftOptions shift;         // for the damping estimate at an indefinite start
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
