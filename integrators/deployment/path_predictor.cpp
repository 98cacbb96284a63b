#include "integrators/deployment/path_predictor.hpp"

#include <cmath>

namespace xshell {

Eigen::VectorXd path_curvature_step(const PathPoint& previous, const PathPoint& last,
                                    const Eigen::VectorXd& tangent, double h,
                                    const std::vector<bool>& comparable) {
  Eigen::VectorXd step = Eigen::VectorXd::Zero(last.q.size());
  const double h0 = last.value - previous.value;
  if (!(std::abs(h0) > 0.0)) return step;
  const double r = h / h0;
  const bool cubic = previous.tangent.size() == last.q.size();
  for (Eigen::Index i = 0; i < step.size(); ++i) {
    if (!comparable[i]) continue;
    const double d = previous.q[i] - last.q[i] + h0 * tangent[i];
    if (!cubic) {
      step[i] = r * r * d;
      continue;
    }
    const double e = h0 * (previous.tangent[i] - tangent[i]);
    step[i] = r * r * (3.0 * d + e) + r * r * r * (2.0 * d + e);
  }
  return step;
}

}  // namespace xshell
