// Statics by Newton's method: find q with grad E(q) = 0 using KINSOL.
//
// One Newton iteration is:
//   1. objective.rebase()  (re-express the unknowns around the current
//      configuration; the Hessian formulas of the rod model are exact only
//      right after it, so every iteration starts right after one: before
//      the first, and after each step, where the gradient of the rebased
//      state serves the convergence test and the next iteration alike),
//   2. one KINSOL iteration on F(q) = grad E(q) (KINSetNumMaxIters(1), one
//      KINSol call per iteration on the same KINSOL memory) with a fresh
//      Jacobian (KINSetMaxSetupCalls(1)): KINSOL evaluates F and calls the
//      linear solver's setup, which factorizes the Hessian with CHOLMOD
//      through a custom SUNLinearSolver (newton_system.hpp).
//   3. the step: by default (LineSearch::Energy) the setup hands the
//      factorization back and the step p = -K^-1 g is backtracked on the
//      energy (descent_step.hpp), along the objective's curve when it has
//      one (the linkage turns its edges: docs/model.md section 9.8); with LineSearch::Kinsol*
//      KINSOL takes it with its own line search (KIN_LINESEARCH, on 1/2 |diag(w) F|^2).
//   4. after a full energy line search step of an unshifted Hessian, up to
//      NewtonOptions::max_chord_corrections steps with the same
//      factorization (chord_correction.hpp), before the rebase.
// KINSOL's function scaling is the objective's gradient weights w, so that
// its own stopping test max_i |w_i F_i| <= tolerance is ours; the driver
// checks the gradient measure before every iteration (a converged start
// does no iteration at all).
//
// An indefinite H is shifted by tau (|H|/|M|) M with tau growing x4 from
// 1e-8 (shifted_factorization.hpp), as in the reference implementation;
// the shifted step is an energy-descent direction. Newton can still
// converge to saddles (e.g. from a symmetric start): every result reports
// `stable`, true only when an unshifted LL^T of the final Hessian succeeds.
// A converged state that is not stable is a saddle or a mechanism; by
// default (NewtonOptions::escape) a saddle is left downhill along its
// direction of most negative curvature and the iterations go on, until a
// stable equilibrium (or a mechanism) is reached
// (integrators/stability/saddle_escape.hpp); each escape counts as an
// iteration and is recorded in SolveResult::saddles_escaped.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "integrators/common/objective.hpp"
#include "integrators/common/solve_result.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"
#include "integrators/stability/saddle_escape.hpp"

namespace xshell {

// How iterations are globalized (which function the backtracking watches).
// Measured (tests/integrators/test_newton.cpp and the 4x4 linkage grid
// under gravity, 444 unknowns): KINSOL's merit line search creeps where
// |g| is much more nonlinear than E (stiff stretching, large rotations,
// curved valleys): extended Rosenbrock 232 iterations vs 22, buckled
// column 47 vs 15, linkage grid > 100 (then KIN_LINESEARCH_NONCONV) vs 5.
enum class LineSearch {
  // Default. Every iteration backtracks on the energy (Armijo), as the
  // reference implementation does; KINSOL provides the iteration (residual,
  // Jacobian setup through the CHOLMOD linear solver) but not the step.
  Energy,
  // Iterations with a positive definite Hessian: KINSOL's line search on
  // the merit function 1/2 |w g|^2. Iterations whose Hessian had to be
  // shifted: the energy line search, because KINSOL rejects energy-descent
  // steps that do not reduce |g|.
  KinsolWithEnergyFallback,
  // Every iteration through KINSOL's line search, shifted or not (stalls
  // at indefinite Hessians; kept for comparison).
  Kinsol,
};

struct NewtonOptions {
  double gradient_tolerance = 2e-8;  // converged when max_i |w_i g_i| <= this (dimensionless)
  int max_iterations = 300;          // from the start, and again from each saddle left
  // Largest step taken (2-norm, in the units of the unknowns); longer
  // Newton steps are scaled down (KINSetMaxNewtonStep, and the energy line
  // search). KINSOL's default (1000 |q0|) is meaningless for unknowns that
  // rebase() resets.
  double max_step = 1e3;
  // The cap grows (grown_step_cap, descent_step.hpp; in the constrained
  // Newton, and in this one with the energy line search): doubled
  // after every capped step taken in full, back to the longer of max_step
  // and the last step after one the line search shortened. For solves that
  // start far from their equilibrium: the stability analysis' held solves,
  // a deployed linkage springing back from its removed loads (scary_face
  // under steel-density gravity, 185 -> 155 iterations, tens of full steps
  // at the cap), a relaxation (the app's: the largest design's descent
  // from its flat saddle, 63 -> 55 iterations), a deployment's steps under
  // the average constraint (deployment.hpp: across a snap-through, tens of
  // capped steps in a row; prescribed joint angles keep the fixed cap).
  bool grow_step_cap = false;
  // Scaled step tolerance (KINSetScaledStepTol, and the same test after an
  // energy line search step): a step with max_i |dq_i| / (1 + |q_i|) below
  // it means the gradient cannot be reduced further (its round-off floor
  // is above gradient_tolerance): the solve stops with
  // SolveStatus::LineSearchFailed.
  double scaled_step_tolerance = 1e-14;
  ShiftOptions shift;  // handling of indefinite Hessians
  LineSearch line_search = LineSearch::Energy;
  // The energy line search follows the objective's curve (the linkage's
  // edge-turning path, docs/model.md section 9.8) instead of the line:
  // large rotations in few iterations. False: the straight line.
  bool follow_path = true;
  // Newton's mixed Hessian (docs/model.md section 9.8): after each energy
  // line search step, the Hessian's stretching geometric stiffness takes
  // the axial forces linearized along the full Newton step instead of
  // those at the new point (Objective::use_mixed_hessian); after a step of
  // KINSOL's line search (LineSearch::Kinsol*), the exact one. The
  // deployment's constrained Newton mixes after its steps along the curve
  // only (ConstrainedNewtonSolver). The energy, the gradient, the
  // equilibrium and the stability test (on the exact Hessian) are
  // unchanged. fish_linkage under gravity: 54 -> 30 iterations; the
  // deployments' benchmark, e.g. scary_face 151 -> 127.
  bool mixed_hessian = true;
  // Chord corrections (chord_correction.hpp, docs/model.md 9.9): after a
  // full energy line search step of an unshifted Hessian (in the
  // constrained Newton, of the Schur complement), at most this many steps
  // with the same factorization while they promise to converge; 0: none.
  // The deployments' benchmark: hourglass 54 -> 35 iterations (92 -> 73
  // factorizations), darth_vader 74 -> 56; the plain relaxation's unloaded
  // equilibrium under steel-density gravity 6 -> 5 and its check 3 -> 2.
  int max_chord_corrections = 3;
  SaddleEscapeOptions escape;  // leaving converged saddles (enabled by default)
};

// One per iteration, and one for the initial state (iteration 0).
struct NewtonReport {
  int iteration = 0;    // iterations done
  double energy = 0.0;  // after the iteration
  double gradient_measure = 0.0;
  double step_norm = 0.0;   // max_i |dq_i| of the step taken (unknowns before the next rebase)
  long factorizations = 0;  // numeric Cholesky factorizations in this iteration
  bool shifted = false;     // the Hessian was indefinite and had to be shifted
  bool energy_line_search = false;     // the step was globalized on the energy (not by KINSOL)
  double shift = 0.0;                  // coefficient of M in the shift (0 if none)
  double seconds = 0.0;                // wall time of the iteration
  double hessian_seconds = 0.0;        // of which Hessian assembly
  double factorization_seconds = 0.0;  // and numeric factorizations (shifted retries included)
  int chord_corrections = 0;  // taken after the step (NewtonOptions::max_chord_corrections)
};

struct NewtonCallbacks {
  std::function<void(const NewtonReport&)> on_iteration;  // optional
  const std::atomic<bool>* stop = nullptr;                // optional; checked before each iteration
};

// Newton's result is the common one (solve_result.hpp): LinearSolverFailed
// when the Hessian could not be factorized even shifted; LineSearchFailed
// when no step was acceptable (either line search), at stagnation on the
// round-off floor, or when the objective rejected every trial point;
// iterations counts completed iterations (a failed one is not counted).
using NewtonResult = SolveResult;

// A Newton solver bound to one objective (its size must not change). Keeps
// the KINSOL memory and the CHOLMOD symbolic analysis across solve() calls,
// e.g. over the steps of a deployment. On failure the objective is left at
// the last iterate that was accepted (finite energy and gradient).
class NewtonSolver {
 public:
  NewtonSolver(Objective& objective, NewtonOptions options = {});
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  NewtonResult solve(const NewtonCallbacks& callbacks = {});

  const NewtonOptions& options() const { return options_; }
  // Exchanges the CHOLMOD solver with `other`: its symbolic analysis, its
  // last factorization and its counters, moved, not copied. Lent before a
  // solve, a solver whose Hessian has the pattern it last saw skips its
  // own analysis (and a factorization of the same values); taken back
  // after, it holds the final state's Hessian factorized by the stability
  // test (unless that failed). No effect when n = 0.
  void swap_cholesky(CholeskySolver& other);
  // Counters of the CHOLMOD solver kept across solves (all zero for n = 0).
  CholeskyStats cholesky_stats() const;

 private:
  struct Impl;
  Objective& objective_;
  NewtonOptions options_;
  std::unique_ptr<Impl> impl_;
};

// One-off convenience: NewtonSolver(objective, options).solve(callbacks).
NewtonResult solve_newton(Objective& objective, const NewtonOptions& options = {},
                          const NewtonCallbacks& callbacks = {});

}  // namespace xshell
