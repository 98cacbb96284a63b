// Statics by classic dynamic relaxation with kinetic damping (Day 1965;
// Barnes 1999; Adriaenssens & Barnes 2001): a third path to grad E = 0,
// explicit and without any factorization, kept as a baseline.
//
// Leapfrog (central differences) on the free unknowns q, time step dt = 1,
// residual R = -grad E:
//   v_{n+1/2} = v_{n-1/2} + dt M^-1 R_n,      q_{n+1} = q_n + dt v_{n+1/2},
// and, right after a start or a reset (at rest), Barnes's half step
// v_{1/2} = (dt/2) M^-1 R_0, with which a linear mode from rest follows
// a_n = a_0 cos(omega n) exactly (cos omega = 1 - dt^2 lambda / 2): its
// potential energy never exceeds the starting one.
//
// Fictitious masses (diagonal): m_i = safety (dt^2/4) sum_j |K_ij| over the
// whole row i of the free Hessian K (thetas and joint rotations included:
// they are unknowns with rows of their own). By Gerschgorin every eigenvalue
// of M^-1 K is at most max_i sum_j |K_ij| / m_i = 4 / (safety dt^2), and the
// leapfrog is stable for dt^2 lambda_max < 4: any safety > 1 is stable while
// K stays what it was; Barnes uses 2 (m_i = dt^2/2 sum_j |K_ij|). A
// unit-independent variant of the bound: MassBound::ScaledRowSum. The masses
// are refreshed from the current Hessian only at resets (v = 0, so the
// kinetic energies compared for peaks always use one mass matrix): at the
// first reset after mass_refresh_interval iterations, and whenever the energy
// rises above its value at the last reset (something the stable leapfrog
// from rest cannot do on a quadratic energy), with the safety multiplied by
// mass_growth when that happens again soon after.
//
// Kinetic damping: KE_{n+1/2} = 1/2 v'Mv. When KE_{n+1/2} < KE_{n-1/2} a
// peak has been passed: the velocities are zeroed and the state moved back to
// the peak (PeakLocation below), then the leapfrog restarts with a half step.
// The objective is rebased (objective.rebase) at every reset, where v = 0
// makes it free, and after rebase_interval iterations without a reset, with
// v transformed.
//
// Stopping criterion, as the other paths: gradient measure <= tolerance and
// KE <= kinetic_tolerance * max(|E_0 - E|, |E|). The Hessian is only read for
// the mass rows; the single factorization is the final stability check
// (stable: an unshifted LL^T of the final Hessian succeeds).
//
// Iterations grow like sqrt(cond(M^-1 K)): thousands where Newton needs tens.
// Each costs one gradient, one energy and one set(); a mass refresh costs
// one Hessian assembly. The model's gradient is assembled in OpenMP loops:
// on small linkages, or on a loaded machine, run with OMP_NUM_THREADS=1
// (the threads' spin-waits cost more than the work: 15x on the tests).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <atomic>
#include <functional>
#include <string>

#include "integrators/common/objective.hpp"
#include "integrators/common/progress_watch.hpp"
#include "integrators/common/solve_result.hpp"
#include "integrators/kinetic_damping/kinetic_damping_watch.hpp"

namespace xshell {

// Where a reset puts the state once a kinetic-energy peak has been passed
// (detected at step n: KE_{n+1/2} < KE_{n-1/2}, q_{n+1} already computed).
enum class PeakLocation {
  // Barnes's formula
  //   q* = q_{n+1} - 1.5 dt v_{n+1/2} + 0.5 dt^2 M^-1 R_n.
  // Since q_{n+1} = q_n + dt v_{n+1/2} and v_{n+1/2} = v_{n-1/2} + dt M^-1 R_n,
  // q* = q_n - 0.5 dt v_{n-1/2} = (q_{n-1} + q_n) / 2: the state at
  // t_{n-1/2}, the time of the largest kinetic-energy sample.
  Barnes,
  // Peak time from the parabola through the last three samples
  // KE_{n-3/2}, KE_{n-1/2}, KE_{n+1/2} (at tau = -1, 0, 1 around t_{n-1/2}):
  //   tau* = (KE_{n-3/2} - KE_{n+1/2}) / (2 (KE_{n-3/2} - 2 KE_{n-1/2} + KE_{n+1/2})),
  // clamped to [-1/2, 1/2]; the state there on the leapfrog's segment
  // q_{n-1} -> q_n (velocity v_{n-1/2}): q* = q_n - (1/2 - tau*) dt v_{n-1/2}.
  // Barnes's point when tau* = 0 (or fewer than three samples since the reset).
  // Nearer the true peak, but more resets than Barnes's midpoint, which
  // filters the fastest modes (docs/tuning.md).
  Parabola,
};

// Which Gerschgorin bound gives the fictitious masses (both bound every
// eigenvalue of M^-1 K by 4 / (safety dt^2)).
enum class MassBound {
  // Barnes: m_i ~ sum_j |K_ij|. Sums entries of different units where
  // positions meet angles, so the masses (and the iteration count) depend on
  // the length unit (docs/tuning.md).
  RowSum,
  // m_i ~ sum_j |K_ij| sqrt(K_ii / K_jj): Gerschgorin on the Jacobi-scaled
  // B = D^-1/2 K D^-1/2 (D = diag |K_ii|), M = D^1/2 diag(sum_j |B_ij|) D^1/2.
  // M^-1 K is similar to diag(sum_j |B_ij|)^-1 B, whose rows sum to 1 in
  // absolute value: the same bound, and invariant under any rescaling of
  // the unknowns (units), except for rows whose diagonal is below the floor
  // of scaled_fictitious_mass.
  ScaledRowSum,
};

// The masses of MassBound::ScaledRowSum for safety dt^2 / 4 = 1 (|K_ii|
// below 1e-12 max_j |K_jj| raised to it; m_i >= |K_ii|).
Eigen::VectorXd scaled_fictitious_mass(const Eigen::SparseMatrix<double>& H);

struct KineticDampingOptions {
  double gradient_tolerance = 2e-8;  // converged when max_i |w_i g_i| <= this (dimensionless)
  double kinetic_tolerance = 1e-12;  // relative to the energy scale, as DynamicsOptions
  long max_iterations = 1000000;     // leapfrog steps
  // m_i = safety (dt^2/4) sum_j |K_ij|; > 1 for stability; Barnes: 2.
  double mass_safety = 2.0;
  MassBound mass_bound = MassBound::RowSum;
  // Factor on the safety when the energy rises twice within
  // mass_refresh_interval iterations, or a step is rejected (invalid or
  // non-finite configuration).
  double mass_growth = 2.0;
  // Masses are refreshed at the first reset after this many iterations.
  long mass_refresh_interval = 100;
  // Iterations without a reset after which the objective is rebased anyway
  // (velocities transformed). >= 1.
  long rebase_interval = 50;
  PeakLocation peak = PeakLocation::Barnes;
  // A rise of E above its value at the last reset larger than this times
  // max(|E_reset|, E_0 - E_reset) counts as an energy rise (round-off and
  // the leapfrog's O(dt^2) error on nonlinear energies are below it).
  double energy_rise_tolerance = 1e-10;
  // Rejected steps (set() threw std::domain_error, or NaN/inf) without a
  // kinetic-energy peak between them before giving up (each raises the
  // masses, so a state pressed against an invalid region creeps towards it
  // with ever shorter steps).
  int max_rejected_steps = 30;
  // Stops a run that stagnates at the round-off floor of the gradient
  // (IntegratorFailed, reason "stagnation: ...") or that accelerates away
  // from the best state it found (Diverged, reason "diverging: ..."):
  // kinetic_damping_watch.hpp. On by default.
  KineticDampingWatchOptions watch;
  // The windows of progress_watch.hpp, as damped dynamics uses them: off by
  // default (window 0), because on real linkages (uniform_linkage,
  // sphere_open) kinetic damping near a 1e-8 tolerance stays 20,000
  // iterations without halving its gradient and then converges: `watch`
  // tells stagnation apart. E.g. {2000, 1e-12, 10, false}.
  ProgressWatchOptions progress = {0, 1e-12, 10, false};
};

// One per iteration (leapfrog step), and one for the initial state (0).
struct KineticDampingReport {
  long iteration = 0;
  double energy = 0.0;          // E at the state after the iteration (after a reset, the peak)
  double kinetic_energy = 0.0;  // 1/2 v'Mv there (0 after a reset)
  double gradient_measure = 0.0;
  double step_norm = 0.0;       // max_i |dq_i| of the leapfrog step (before any reset)
  bool reset = false;           // a kinetic-energy peak was passed: v = 0, state moved back
  bool energy_rise = false;     // E rose above its value at the last reset: v = 0, masses refreshed
  bool mass_refreshed = false;  // masses recomputed from the Hessian in this iteration
  bool rejected = false;        // the step was rejected (invalid or NaN): state kept, masses raised
  double seconds = 0.0;         // wall time of the iteration
};

struct KineticDampingCallbacks {
  std::function<void(const KineticDampingReport&)> on_iteration;  // optional
  const std::atomic<bool>* stop = nullptr;  // optional; checked before each iteration
};

// The common result (solve_result.hpp) and what kinetic damping adds.
// iterations counts leapfrog steps; InvalidConfiguration: steps kept
// leaving the valid configurations, even with heavier masses; NonFinite
// also when steps kept producing NaN/inf; Diverged and IntegratorFailed
// (stagnation) as options.watch (and options.progress, when on) say. factorizations: the stability
// check only.
struct KineticDampingResult : SolveResult {
  long resets = 0;          // kinetic-energy peaks
  long energy_rises = 0;    // resets because E rose (see options)
  long rejected_steps = 0;  // steps rejected and retried with heavier masses
  long mass_refreshes = 0;  // Hessian reads for the masses, the first included
  long rebases = 0;
  long gradient_evaluations = 0;
  double mass_safety = 0.0;  // at the end (grows with mass_growth)
  double kinetic_energy = 0.0;
};

// Relaxes from the objective's current configuration, at rest. On failure
// the objective is left at the last accepted state.
KineticDampingResult solve_kinetic_damping(Objective& objective,
                                           const KineticDampingOptions& options = {},
                                           const KineticDampingCallbacks& callbacks = {});

}  // namespace xshell
