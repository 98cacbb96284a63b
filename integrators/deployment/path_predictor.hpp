// The curvature terms of a continuation's predictor (docs/model.md 9.3):
// along an equilibrium path q(A) with the tangent t1 = dq/dA at the last
// equilibrium q1 (at A) and the equilibrium before it, q0 at A - h0,
//  - the quadratic through q0 with the tangent t1 predicts
//      q(A + h) ~ q1 + h t1 + (h/h0)^2 D,   D = q0 - q1 + h0 t1,
//    with an error O(h^3) (the tangent alone: O(h^2));
//  - when the tangent t0 at q0 is known too, the cubic (Hermite) through
//    both equilibria and both tangents predicts
//      q(A + h) ~ q1 + h t1 + (h/h0)^2 (3 D + h0 E) + (h/h0)^3 (2 D + h0 E),
//    E = t0 - t1, with an error O(h^4).
//  - with the path's second derivative k1 = q''(A) at q1 (from the
//    gradient's third derivative along t1, ConstrainedNewtonSolver::
//    second_derivative), the Taylor polynomial q1 + h t1 + (h^2/2) k1,
//    error O(h^3), which needs no earlier equilibrium (so it serves right
//    after a jump off the path) and covers every unknown, and the cubic
//    through q0 that has it at q1:
//      q(A + h) ~ q1 + h t1 + (h^2/2) k1 + (h/h0)^3 ((h0^2/2) k1 - D),
//    error O(h^4).
// All these terms are orthogonal to the constraint's coefficients a when
// a . t0 = a . t1 = 1 and a . k1 = 0 (a . D = 0, a . E = 0): the
// prediction stays on a . q = A + h.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace xshell {

struct PathPoint {
  Eigen::VectorXd q;   // an equilibrium's unknowns
  double value = 0.0;  // the path parameter there (the average opening angle)
  // dq/dA there, once computed (empty until then).
  Eigen::VectorXd tangent = {};
  // The rotation joints' frames there (joint_charts.hpp), which say what
  // its omegas mean.
  std::vector<Eigen::Matrix3d> frames = {};
  // d^2q/dA^2 there, once computed (empty until then), in its own charts.
  Eigen::VectorXd curvature = {};
};

// The terms beyond q1 + h t1 above (cubic when previous.tangent has q's
// size, else quadratic), on the unknowns marked in `comparable` (those
// whose values at q1 and q0 mean the same thing), 0 on the others and when
// h0 = 0. Sizes: q, t, previous.q and comparable alike.
Eigen::VectorXd path_curvature_step(const PathPoint& previous, const PathPoint& last,
                                    const Eigen::VectorXd& tangent, double h,
                                    const std::vector<bool>& comparable);

// The Taylor cubic's terms beyond q1 + h t1 above: (h^2/2) k1 on every
// unknown, plus the cubic's term on those marked in `comparable` (only
// (h^2/2) k1 when h0 = 0). Sizes: q, t, k1, previous.q and comparable alike.
Eigen::VectorXd taylor_cubic_step(const PathPoint& previous, const PathPoint& last,
                                  const Eigen::VectorXd& tangent, const Eigen::VectorXd& curvature,
                                  double h, const std::vector<bool>& comparable);

// The Hermite polynomial that has q1, t1, k1 at q1 and q0, t0 (and k0 =
// previous.curvature when it has q's size) at q0: a quartic
// (error O(h^5)) or a quintic (error O(h^6)); its terms beyond q1 + h t1.
// Unknowns not marked in `comparable` get (h^2/2) k1 only; those marked in
// `comparable` but not in `curvature_comparable` (whose second derivatives
// at q0 and q1 are in different charts) the quartic's terms.
Eigen::VectorXd hermite_taylor_step(const PathPoint& previous, const PathPoint& last,
                                    const Eigen::VectorXd& tangent,
                                    const Eigen::VectorXd& curvature, double h,
                                    const std::vector<bool>& comparable,
                                    const std::vector<bool>& curvature_comparable);

// D3E[t, t] at q by the central second difference of the gradient along t,
//   (g(q + eps t) - 2 g(q) + g(q - eps t)) / eps^2,
// error O(eps^2) (the round-off: eps_machine |g| / eps^2). `gradient`
// evaluates g at a point (and may throw; so does this then), at q last.
Eigen::VectorXd gradient_second_difference(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& gradient,
    const Eigen::VectorXd& q, const Eigen::VectorXd& t, double eps);

// The same, empty instead when `gradient` rejects a point of the
// difference (std::domain_error: then evaluated at q once more, so that
// the caller's state is left at q) or a value is not finite.
Eigen::VectorXd gradient_second_difference_or_empty(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& gradient,
    const Eigen::VectorXd& q, const Eigen::VectorXd& t, double eps);

}  // namespace xshell
