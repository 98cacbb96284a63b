// Leaving a saddle: when a solver has converged to an equilibrium whose
// free Hessian H is not positive definite, the state is a saddle (some
// direction lowers the energy) or a mechanism (zero modes only). A saddle
// is information, not an answer: the solvers move off it downhill along
// the direction of most negative curvature and iterate on, until they reach
// a stable equilibrium (docs/model.md section 9.5).
//
// The direction is the lowest eigenvector of H phi = lambda M phi (M the
// lumped masses, so that lambda does not depend on how the unknowns mix
// lengths and angles), found by shift-invert Lanczos on a CHOLMOD
// factorization of H - sigma M (eigen_modes.hpp), which reuses the symbolic
// analysis of the solver's own Cholesky factorization. lambda counts as
// negative curvature when lambda < -relative_threshold |H|_F / |m|_2 (the
// scale of the solvers' shifts, shifted_factorization.hpp): a mechanism's
// zero modes sit at round-off, far above that. A mode of negative curvature
// is then also required to lower the energy beyond round-off.
//
// Branch choice: of the two signs of phi (the two sides a symmetric state
// can leave by), the escape takes the one with bias . phi > 0, where bias
// is a vector over the free unknowns chosen by the caller (for a linkage:
// the joints' mean displacement along the buckling direction,
// branch_bias()). When that product vanishes (a mode that moves no joint
// along the direction), the sign makes phi's largest entry positive, so the
// result never depends on round-off.
//
// The step follows the bifurcating branch to second order,
//   q = q0 + t phi + t^2 w,   H w = -1/2 P D3E[phi, phi]
// (phi scaled to a largest entry of 1, P removing phi's component, H
// shifted by -2 lambda M to be definite): along the straight line q0 + t
// phi the rods stretch at second order and the energy rises again after a
// short step (manta_ray's deployment: 1 mm and 0.08 of the 95 energy
// units down to the buckled state; along the bend 31 mm and 61 units),
// and shifted Newton steps crept the rest of the way. t doubles from
// 1e-3 max(1, |q0|_inf) while the energy falls (halving first while the
// first trial does not lower it), the lowest energy of the trials kept;
// without w (the straight line) when D3E or the factorization is not
// available (docs/model.md 9.5).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "integrators/common/objective.hpp"
#include "integrators/common/solve_result.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

struct SaddleEscapeOptions {
  bool enabled = true;   // false: report saddles as they are ("solver.escape_saddles")
  int max_escapes = 10;  // escapes per solve
  // Over the free unknowns (empty: no preference): phi is signed so that
  // bias . phi > 0.
  Eigen::VectorXd bias;
  // lambda < -relative_threshold |H|_F / |m|_2 is negative curvature.
  double relative_threshold = 1e-12;
  // A trial lowers the energy when E < E0 - energy_noise |E0|.
  double energy_noise = 1e-13;
};

enum class EscapeOutcome {
  Escaped,              // moved downhill off a saddle; the objective is at the new point
  NoNegativeCurvature,  // lambda_min above the threshold: a mechanism or a minimum
  NoDescent,            // no trial lowered the energy beyond round-off; objective unchanged
  NoMode,               // the eigensolver failed; objective unchanged
};

struct EscapeResult {
  EscapeOutcome outcome = EscapeOutcome::NoMode;
  SaddleRecord saddle;     // energy and lambda_min at the start
  Eigen::VectorXd mode;    // phi, signed and scaled as taken (empty unless a mode was found)
  double amplitude = 0.0;  // t of the step taken
};

// The lowest mode of H (the objective's Hessian at its current state) with
// `solver` (its symbolic analysis reused), and when it has negative
// curvature the step downhill along it. H: free Hessian, both triangles;
// mass: positive, size n.
EscapeResult escape_saddle(Objective& objective, const Eigen::SparseMatrix<double>& H,
                           const Eigen::VectorXd& mass, CholeskySolver& solver,
                           const SaddleEscapeOptions& options);

// The two parts of escape_saddle, for solvers whose Hessian lives in other
// coordinates than their objective (the constrained Newton's null space).
struct NegativeMode {
  bool found = false;     // the eigensolver converged
  bool negative = false;  // eigenvalue below the threshold: negative curvature
  double eigenvalue = 0.0;
  Eigen::VectorXd vector;  // signed_direction() of the mode (bias in H's coordinates)
};
NegativeMode negative_mode(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                           CholeskySolver& solver, const SaddleEscapeOptions& options);
// The step q0 + t d + t^2 bend (the trials above; an empty bend: the
// straight line) from the objective's state q0; returns t (0: no trial
// lowered the energy, the objective back at q0).
double step_downhill(Objective& objective, const Eigen::VectorXd& direction,
                     const SaddleEscapeOptions& options, const Eigen::VectorXd& bend = {});

// For the bend: D3E[d, d] at the objective's state, by the gradient's central
// second difference (step 1e-3; d scaled to a largest entry of 1), the
// objective left there; empty when a point of the difference is invalid
// or a value not finite.
Eigen::VectorXd third_derivative_along(Objective& objective, const Eigen::VectorXd& d);

// The bend w = -1/2 (H - 2 lambda M)^-1 third, without its component along
// the mode (M-orthogonal), with `solver` (its symbolic analysis reused);
// H - 2 lambda M is positive definite when lambda is H's lowest eigenvalue.
// Empty when third is, lambda >= 0, or the factorization fails.
Eigen::VectorXd bend_of_mode(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                             double eigenvalue, const Eigen::VectorXd& mode,
                             const Eigen::VectorXd& third, CholeskySolver& solver);

// phi signed by the branch rule above (bias . phi > 0, else largest entry
// positive) and scaled to a largest entry of magnitude 1.
Eigen::VectorXd signed_direction(const Eigen::VectorXd& phi, const Eigen::VectorXd& bias);

}  // namespace xshell
