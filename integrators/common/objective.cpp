#include "integrators/common/objective.hpp"

namespace xshell {

double gradient_measure(const Objective& objective) {
  const Eigen::VectorXd g = objective.gradient();
  if (g.size() == 0) return 0.0;
  return (objective.gradient_weights().array() * g.array()).abs().maxCoeff();
}

}  // namespace xshell
