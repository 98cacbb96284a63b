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
#include <functional>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/solve_result.hpp"
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
  // energy_descent_step: backtrack along the objective's curve when it has
  // one (Objective::begin_path), not along the line.
  bool follow_path = true;
  // The factorization is of the unshifted Hessian: the step is Newton's
  // (Objective::begin_path's newton_step).
  bool newton_step = false;
  // On a path, a full step that was accepted is doubled while the merit
  // keeps falling (with the Armijo test), up to this multiple (not tried
  // where the quadratic through the start's merit and slope and the full
  // step's merit says that doubling cannot fall further): Newton's
  // quadratic model measures curvature along the line, which a curved
  // valley (a buckled column turning its plane, docs/model.md section 9.8)
  // has and the path does not, so the Newton step can fall far short.
  double max_expansion = 64.0;
  // energy_descent_step: once p is known, the objective's Hessian becomes
  // the mixed one along p (Objective::use_mixed_hessian), for the next
  // iteration wherever the step ends.
  bool mixed_hessian = false;
};

struct DescentStepResult {
  bool accepted = false;
  bool capped = false;              // p was scaled down to max_step
  double step_fraction = 0.0;       // alpha of the accepted step q0 + alpha p
  double energy = 0.0;              // E(q0 + alpha p) when accepted
  int trials = 0;                   // energy evaluations attempted
  int rejected_configurations = 0;  // trial points that were invalid or NaN
};

// The step cap after an accepted step (NewtonOptions::grow_step_cap) of
// `taken` (2-norm), the fraction `fraction` of the Newton step capped at
// `cap` (`capped`: it was longer): doubled when the capped step was taken
// in full (the quadratic model held that far: a linkage springing back
// under a removed load, or descending from a saddle, each full step of
// max_step lowering the energy), else max_step or the length the line
// search found, whichever is longer.
double grown_step_cap(double cap, bool capped, double max_step, double taken, double fraction);

// From q0 (where the objective is, with energy e0 and gradient g0), takes
// q0 + alpha p with p = -K^-1 g0 (K factorized in `factor`), the largest
// alpha = shrink^k with E(q0 + alpha p) <= e0 + c1 alpha g0.p. On success
// the objective is at the new point; otherwise it is back at q0.
DescentStepResult energy_descent_step(ObjectiveEvaluator& evaluator, CholeskySolver& factor,
                                      const Eigen::VectorXd& q0, double e0,
                                      const Eigen::VectorXd& g0,
                                      const DescentStepOptions& options = {});

// What the backtracking watches along a given direction (backtrack_on_energy).
struct BacktrackingMerit {
  // phi(E, q) at a trial point q of energy E; empty: phi = E.
  std::function<double(double energy, const Eigen::VectorXd& q)> merit;
  double phi0 = 0.0;   // phi at q0
  double slope = 0.0;  // the slope in the Armijo test (< 0 for a descent direction)
  // The end game's test, called at the full step (the objective there)
  // when it changed the energy by less than endgame_energy_change |E0|:
  // true when the scaled gradient fell, which accepts the step.
  std::function<bool()> progress;
  // The trial point at alpha, on a curve leaving q0 with tangent p
  // (Objective::begin_path); empty: q0 + alpha p. May throw
  // std::domain_error (an invalid trial point).
  std::function<Eigen::VectorXd(double alpha)> path;
};

// The objective's curve from q0 along p (Objective::begin_path), as a
// BacktrackingMerit::path, or an empty function when it has none. Moves the
// objective to q0.
std::function<Eigen::VectorXd(double)> objective_path(ObjectiveEvaluator& evaluator,
                                                      const Eigen::VectorXd& q0,
                                                      const Eigen::VectorXd& p, bool newton_step);

// The one Armijo backtracking of the energy line searches (this step's and
// the constrained Newton's, constrained_newton.hpp): from q0 (the objective
// there, energy e0) along p, the largest alpha = shrink^k with
//   phi(q0 + alpha p) <= phi0 + c1 alpha slope + energy_noise |e0|,
// or the full step by the end game's test; with merit.path, its point at
// alpha replaces q0 + alpha p (the same slope at alpha = 0), and a full step
// accepted away from the end game is expanded (max_expansion). Trial points
// that are invalid (set() or the path threw std::domain_error) or of
// non-finite energy are recorded in the evaluator and skipped. On success
// the objective is at the new point; otherwise it is back at q0.
DescentStepResult backtrack_on_energy(ObjectiveEvaluator& evaluator, const Eigen::VectorXd& q0,
                                      double e0, const Eigen::VectorXd& p,
                                      const BacktrackingMerit& merit,
                                      const DescentStepOptions& options);

// After a step that was not accepted, with the objective back at its start:
// NonFinite when every trial point failed for non-finite values, else
// LineSearchFailed; the reason names the evaluator's last failure when
// every trial point failed, otherwise "no energy decrease along the <step>".
void fail_line_search(const DescentStepResult& step, const ObjectiveEvaluator& evaluator,
                      const char* step_name, SolveResult& result);

// KINSOL's stagnation measure (KINScSNorm with unit scaling) of the step
// q0 -> q: max_i |q_i - q0_i| / (1 + |q_i|).
double scaled_step_length(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& q0);

}  // namespace xshell
