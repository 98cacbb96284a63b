// The curvature term of a continuation's predictor (docs/model.md 9.3):
// along an equilibrium path q(A) with the tangent t = dq/dA at the last
// equilibrium q (at A), the quadratic through the equilibrium before it,
// q_prev at A - h_prev, predicts
//   q(A + h) ~ q + h t + h^2 c,   c = (q_prev - q + h_prev t) / h_prev^2,
// with an error O(h^3) (the tangent alone: O(h^2)).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace xshell {

struct PathPoint {
  Eigen::VectorXd q;   // an equilibrium's unknowns
  double value = 0.0;  // the path parameter there (the average opening angle)
};

// h^2 c on the unknowns marked in `comparable` (those whose values at q and
// q_prev mean the same thing), 0 on the others and when h_prev = 0.
// Sizes: q, t, previous.q and comparable alike.
Eigen::VectorXd path_curvature_step(const PathPoint& previous, const PathPoint& last,
                                    const Eigen::VectorXd& tangent, double h,
                                    const std::vector<bool>& comparable);

}  // namespace xshell
