// A (modified) Newton step globalized on the energy: the default step of
// the Newton solver (LineSearch::Energy) and the fallback for shifted
// Hessians otherwise.
//
// Why not KINSOL's line search: KINSOL backtracks on the merit function
// 1/2 |diag(w) g|^2 and assumes the step solves H p = -g exactly. A shifted
// step p = -(H + sigma M)^-1 g is a descent direction of the energy (the
// matrix is positive definite) but in general not of the merit function,
// whose gradient is H diag(w)^2 g; KINSOL then backtracks to nothing
// (KIN_LINESEARCH_NONCONV) or creeps towards a stationary point of |g| that
// is not an equilibrium. Even unshifted, |g| is far more nonlinear than E
// when stretching is stiff and rotations large, and KINSOL's steps shrink
// (newton.hpp lists the measured iteration counts). The reference
// implementation backtracks on the energy (Armijo), which this step does.
#pragma once

#include <Eigen/Core>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

struct DescentStepOptions {
  double sufficient_decrease = 1e-4;  // Armijo constant c1
  double shrink = 0.5;                // step multiplier per backtrack
  int max_backtracks = 60;
  double max_step = 1e3;  // cap on the 2-norm of the full step
  // Energy changes below energy_noise * |E| are round-off: such a step is
  // accepted as long as it does not raise the energy by more than that, so
  // that iterations converging to a (symmetric) saddle do not stall.
  double energy_noise = 1e-14;
  // End game: when the full step changes the energy by less than
  // endgame_energy_change * |E| (the energy is then dominated by round-off
  // of its much larger parts), the full step is accepted if it lowers the
  // scaled gradient norm |diag(w) g|: near a minimum the Newton step is
  // trustworthy and the energy can no longer tell progress.
  double endgame_energy_change = 1e-8;
};

struct DescentStepResult {
  bool accepted = false;
  double step_fraction = 0.0;       // alpha of the accepted step q0 + alpha p
  double energy = 0.0;              // E(q0 + alpha p) when accepted
  int trials = 0;                   // energy evaluations attempted
  int rejected_configurations = 0;  // trial points that were invalid or NaN
};

// From q0 (where the objective is, with energy e0 and gradient g0), takes
// q0 + alpha p with p = -K^-1 g0 (K factorized in `factor`), the largest
// alpha = shrink^k with E(q0 + alpha p) <= e0 + c1 alpha g0.p. On success
// the objective is at the new point; otherwise it is back at q0.
DescentStepResult energy_descent_step(ObjectiveEvaluator& evaluator, CholeskySolver& factor,
                                      const Eigen::VectorXd& q0, double e0,
                                      const Eigen::VectorXd& g0,
                                      const DescentStepOptions& options = {});

}  // namespace xshell
