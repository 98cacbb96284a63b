#include "integrators/newton/descent_step.hpp"

#include <cmath>
#include <stdexcept>

namespace xshell {

DescentStepResult energy_descent_step(ObjectiveEvaluator& evaluator, CholeskySolver& factor,
                                      const Eigen::VectorXd& q0, double e0,
                                      const Eigen::VectorXd& g0,
                                      const DescentStepOptions& options) {
  Eigen::VectorXd p = -factor.solve(g0);
  const double length = p.norm();
  if (!std::isfinite(length)) return {};
  if (length > options.max_step) p *= options.max_step / length;
  const double slope = g0.dot(p);  // < 0: K is positive definite
  if (!(slope < 0.0)) return {};

  BacktrackingMerit energy;
  energy.phi0 = e0;
  energy.slope = slope;
  energy.progress = [&] {
    const Eigen::VectorXd w = evaluator.objective().gradient_weights();
    const Eigen::VectorXd g = evaluator.objective().gradient();
    return g.allFinite() &&
           (w.array() * g.array()).matrix().norm() < (w.array() * g0.array()).matrix().norm();
  };
  return backtrack_on_energy(evaluator, q0, e0, p, energy, options);
}

DescentStepResult backtrack_on_energy(ObjectiveEvaluator& evaluator, const Eigen::VectorXd& q0,
                                      double e0, const Eigen::VectorXd& p,
                                      const BacktrackingMerit& merit,
                                      const DescentStepOptions& options) {
  DescentStepResult result;
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
    const double phi = merit.merit ? merit.merit(energy, trial) : energy;
    const bool accepted =
        phi <= merit.phi0 + options.sufficient_decrease * alpha * merit.slope + slack ||
        (k == 0 && std::abs(energy - e0) <= options.endgame_energy_change * std::abs(e0) &&
         merit.progress && merit.progress());
    if (accepted) {
      result.accepted = true;
      result.step_fraction = alpha;
      result.energy = energy;
      return result;
    }
  }
  evaluator.move_to(q0);
  return result;
}

void fail_line_search(const DescentStepResult& step, const ObjectiveEvaluator& evaluator,
                      const char* step_name, SolveResult& result) {
  const bool all_rejected = step.trials > 0 && step.rejected_configurations == step.trials;
  result.status = all_rejected && evaluator.last_failure() == EvaluationFailure::NonFinite
                      ? SolveStatus::NonFinite
                      : SolveStatus::LineSearchFailed;
  result.reason = all_rejected
                      ? "the objective failed at every trial point: " + evaluator.last_message()
                      : std::string("no energy decrease along the ") + step_name;
}

double scaled_step_length(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& q0) {
  return ((q - q0).array().abs() / (1.0 + q.array().abs())).maxCoeff();
}

}  // namespace xshell
