#include "integrators/common/objective.hpp"

#include <stdexcept>

namespace xshell {

Eigen::VectorXd Objective::path_point(double) {
  throw std::logic_error("Objective::path_point without a path (begin_path returned false)");
}

double gradient_measure(const Objective& objective) {
  const Eigen::VectorXd g = objective.gradient();
  if (g.size() == 0) return 0.0;
  return (objective.gradient_weights().array() * g.array()).abs().maxCoeff();
}

}  // namespace xshell
