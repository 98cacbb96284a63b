#include "integrators/newton/descent_step.hpp"

#include <cmath>
#include <stdexcept>

namespace xshell {

DescentStepResult energy_descent_step(ObjectiveEvaluator& evaluator, CholeskySolver& factor,
                                      const Eigen::VectorXd& q0, double e0,
                                      const Eigen::VectorXd& g0,
                                      const DescentStepOptions& options) {
  DescentStepResult result;
  Eigen::VectorXd p = -factor.solve(g0);
  const double length = p.norm();
  if (!std::isfinite(length)) return result;
  if (length > options.max_step) p *= options.max_step / length;
  const double slope = g0.dot(p);  // < 0: K is positive definite
  if (!(slope < 0.0)) return result;

  double alpha = 1.0;
  for (int k = 0; k <= options.max_backtracks; ++k, alpha *= options.shrink) {
    const Eigen::VectorXd trial = q0 + alpha * p;
    if (trial == q0) break;  // the step vanished in round-off
    ++result.trials;
    double energy = 0.0;
    try {
      energy = evaluator.energy_at(trial);
    } catch (const std::domain_error& e) {
      evaluator.record(EvaluationFailure::InvalidConfiguration, e.what());
      ++result.rejected_configurations;
      continue;
    }
    if (!std::isfinite(energy)) {
      evaluator.record(EvaluationFailure::NonFinite, "the energy is not finite");
      ++result.rejected_configurations;
      continue;
    }
    const double slack = options.energy_noise * std::abs(e0);
    if (energy <= e0 + options.sufficient_decrease * alpha * slope + slack) {
      result.accepted = true;
      result.step_fraction = alpha;
      result.energy = energy;
      return result;
    }
    if (k == 0 && std::abs(energy - e0) <= options.endgame_energy_change * std::abs(e0)) {
      const Eigen::VectorXd w = evaluator.objective().gradient_weights();
      const Eigen::VectorXd g = evaluator.objective().gradient();
      if (g.allFinite() &&
          (w.array() * g.array()).matrix().norm() < (w.array() * g0.array()).matrix().norm()) {
        result.accepted = true;
        result.step_fraction = alpha;
        result.energy = energy;
        return result;
      }
    }
  }
  evaluator.move_to(q0);
  return result;
}

}  // namespace xshell
