#include "integrators/deployment/path_predictor.hpp"

#include <cmath>

namespace xshell {

Eigen::VectorXd path_curvature_step(const PathPoint& previous, const PathPoint& last,
                                    const Eigen::VectorXd& tangent, double h,
                                    const std::vector<bool>& comparable) {
  Eigen::VectorXd step = Eigen::VectorXd::Zero(last.q.size());
  const double h_prev = last.value - previous.value;
  if (!(std::abs(h_prev) > 0.0)) return step;
  const double scale = (h * h) / (h_prev * h_prev);
  for (Eigen::Index i = 0; i < step.size(); ++i)
    if (comparable[i]) step[i] = scale * (previous.q[i] - last.q[i] + h_prev * tangent[i]);
  return step;
}

}  // namespace xshell
