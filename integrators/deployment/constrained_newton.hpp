// Newton's method under the average constraint a . q = A
// (average_constraint.hpp): find q and the multiplier tau with
//   grad E(q) = tau a,   a . q = A.
// tau is the actuation torque dE/dA (energy per radian for opening angles).
//
// One iteration, after objective.rebase() (as in newton.hpp), at q with
// gradient g, Hessian H and constraint residual c = A - a . q:
//   Schur complement (the reference implementation's deployment solve):
//   factorize H = L L^T once (CHOLMOD, symbolic analysis kept), solve
//     x1 = H^-1 g,  x2 = H^-1 a,
//   then tau = (c + a . x1) / (a . x2) and p = tau x2 - x1, which solves
//     [H  a; a^T 0] [p; -tau] = [-g; c].
//   Globalized by Armijo backtracking along p on the energy: with c = 0,
//   g . p = -r^T H^-1 r < 0 for r = g - tau a, so p descends on the
//   constraint's plane; from a start off the plane (c != 0), where the
//   energy may have to rise, on the exact penalty E + mu |a . q - A|.
//   Null-space fallback: when LL^T of H fails (H indefinite, e.g. a torque
//   that falls as the linkage opens, or singular beyond round-off: a
//   mechanism, whose free opening mode the constraint removes), the Schur
//   complement has no H^-1; the step is then
//   p = B pz + c a / (a . a) with pz = -(B^T H B)^-1 B^T g on the
//   constraint's null space, B^T H B shifted by multiples of diag(B^T M B)
//   as in shifted_factorization.hpp only when it is itself indefinite.
//   After a full step of the Schur complement, chord corrections with the
//   same factorization (chord_correction.hpp, NewtonOptions::max_chord_corrections).
//   Step cap: |p| <= NewtonOptions::max_step; with grow_step_cap, the cap
//   doubles after every capped step that the line search took in full and
//   returns to the longer of max_step and the accepted step's length after
//   one it shortened.
// Convergence: max_i |w_i (g - tau a)_i| <= gradient_tolerance with the
// least-squares tau = a.g / a.a, and |c| <= constraint_tolerance.
// `stable`: an unshifted LL^T of B^T H B succeeded at the final state (a
// strict minimum on the constraint's plane; H itself may be indefinite).
// Saddles: Newton converges to them as happily as to minima, e.g. a flat
// linkage held in its plane by symmetry while opening it has made buckling
// out of the plane favourable. At a converged but unstable state the solver
// leaves along the most negative curvature direction of B^T H B (its lowest
// mode, mass diag(B^T M B), by shift-invert Lanczos on the reduced solver's
// symbolic analysis; signed by NewtonOptions::escape.bias carried to the
// null space, B^T bias: the user's branch; saddle_escape.hpp), to the
// lowest energy among the trial amplitudes there, and iterates on (the
// reference implementation likewise adds a negative-curvature direction
// near saddles). Each saddle left is recorded in saddles_escaped.
//
// KINSOL is not used: it solves F(q) = 0 and knows nothing of the bordered
// system; the steps, line search and reports follow newton.hpp.
#pragma once

#include <memory>

#include "integrators/deployment/average_constraint.hpp"
#include "integrators/newton/newton.hpp"

namespace xshell {

// The common result (solve_result.hpp) and what the constraint adds.
struct ConstrainedNewtonResult : SolveResult {
  double multiplier = 0.0;           // tau at the final state (least squares a.g / a.a)
  double constraint_residual = 0.0;  // A - a . q at the final state
  int schur_iterations = 0;          // iterations stepped by the Schur complement
  int null_space_iterations = 0;     // by the null-space fallback
  int saddle_escapes = 0;            // moves off an unstable equilibrium (counted as iterations)
  // Converged at the gradient's round-off floor, the measure stagnating
  // within twice the tolerance (the reason says so).
  bool at_round_off_floor = false;
};

// Bound to one objective and constraint (sizes fixed); keeps the two
// CHOLMOD symbolic analyses (H and B^T H B) across solve() calls, e.g. over
// the steps of a deployment. NewtonOptions::line_search is ignored (always
// the energy); NewtonOptions::follow_path applies to the steps of an
// unshifted Hessian (the joints placed too, docs/model.md 9.8), and
// NewtonOptions::mixed_hessian to the steps along that curve (the
// Hessian is the exact one again after every other step, for the
// stability test, tangent() and second_derivative()).
class ConstrainedNewtonSolver {
 public:
  ConstrainedNewtonSolver(Objective& objective, const AverageConstraint& constraint,
                          NewtonOptions options = {});
  ~ConstrainedNewtonSolver();
  ConstrainedNewtonSolver(const ConstrainedNewtonSolver&) = delete;
  ConstrainedNewtonSolver& operator=(const ConstrainedNewtonSolver&) = delete;

  // Solves from the objective's current configuration for the constraint
  // value `target`. On failure the objective is left at the last accepted
  // iterate.
  ConstrainedNewtonResult solve(double target, const NewtonCallbacks& callbacks = {});

  // The tangent dq/dA of the equilibrium path at the objective's current
  // configuration (an equilibrium): the solution t of
  //   [H a; a^T 0] [t; -dtau/dA] = [0; 1],
  // by the Schur complement t = H^-1 a / (a . H^-1 a), or, when H is not
  // positive definite, t = t0 + B tz with t0 = a / (a . a) (the uniform
  // shift) and tz = -(B^T H B)^-1 B^T H t0 (shifted if indefinite). a . t = 1.
  // Returns an empty vector when no factorization could be made.
  // Reuses the stability test's factorization when the configuration is
  // still the last solve's final state (no factorization then when H or
  // B^T H B was positive definite there).
  Eigen::VectorXd tangent();

  // The path's second derivative q'' = d2q/dA2 at the configuration of the
  // last tangent(), from `third` = D3E[t, t], the gradient's second
  // derivative along that tangent t: differentiating grad E(q(A)) =
  // tau(A) a twice gives H q'' + third = tau'' a with a . q'' = 0, so
  //   q'' = -(x - (a . x) t),  x = H^-1 third,
  // or on the null space q'' = -B (B^T H B)^-1 B^T third, with the
  // factorization that tangent() used (no new one). Empty when a
  // factorization has been made since (a solve's, an adjoint's) or the
  // last tangent() failed.
  Eigen::VectorXd second_derivative(const Eigen::VectorXd& third);

  // Numeric factorizations so far (solves, tangents and adjoints).
  long factorizations() const;

  // The adjoint of the equilibrium at the objective's current configuration
  // (inverse design, docs/model.md section 9.7): lambda solving
  //   [H a; a^T 0] [lambda; mu] = [f; 0]   (f: size n),
  // by the Schur complement with one factorization of H (its symbolic
  // analysis kept): x1 = H^-1 f, x2 = H^-1 a, lambda = x1 - (a.x1 / a.x2) x2;
  // or, when H is not positive definite, on the constraint's null space,
  // lambda = B (B^T H B)^-1 B^T f, unshifted (a shift would change the
  // answer). Empty when neither factorizes (an unstable equilibrium).
  Eigen::VectorXd adjoint(const Eigen::VectorXd& f);

  // Residual tolerance on |A - a . q| (units of the averaged unknowns).
  double constraint_tolerance = 1e-12;
  // Escapes from unstable equilibria per solve (0: report saddles as they
  // are); from NewtonOptions::escape (max_escapes, or 0 when not enabled).
  int max_saddle_escapes = 0;

 private:
  struct Impl;
  Objective& objective_;
  const AverageConstraint& constraint_;
  NewtonOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace xshell
