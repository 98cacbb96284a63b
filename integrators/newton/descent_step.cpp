#include "integrators/newton/descent_step.hpp"

#include <algorithm>
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
  const bool capped = length > options.max_step;
  if (capped) p *= options.max_step / length;
  const double slope = g0.dot(p);  // < 0: K is positive definite
  if (!(slope < 0.0)) return {};
  if (options.mixed_hessian) evaluator.objective().use_mixed_hessian(p);  // at q0

  BacktrackingMerit energy;
  energy.phi0 = e0;
  energy.slope = slope;
  energy.progress = [&] {
    const Eigen::VectorXd w = evaluator.objective().gradient_weights();
    const Eigen::VectorXd& g = evaluator.gradient();  // kept for the chord corrections
    return g.allFinite() &&
           (w.array() * g.array()).matrix().norm() < (w.array() * g0.array()).matrix().norm();
  };
  if (options.follow_path) energy.path = objective_path(evaluator, q0, p, options.newton_step);
  DescentStepResult out = backtrack_on_energy(evaluator, q0, e0, p, energy, options);
  out.capped = capped;
  return out;
}

double grown_step_cap(double cap, bool capped, double max_step, double taken, double fraction) {
  if (fraction >= 1.0) return capped ? 2.0 * cap : cap;
  return std::max(max_step, taken);
}

std::function<Eigen::VectorXd(double)> objective_path(ObjectiveEvaluator& evaluator,
                                                      const Eigen::VectorXd& q0,
                                                      const Eigen::VectorXd& p, bool newton_step) {
  evaluator.move_to(q0);
  if (!evaluator.objective().begin_path(p, newton_step)) return {};
  return [&evaluator](double alpha) {
    Eigen::VectorXd q = evaluator.objective().path_point(alpha);
    evaluator.sync();  // path_point may have moved the objective
    return q;
  };
}

namespace {

// After the full step was accepted on a path (at phi, the objective there):
// alpha = 2, 4, ... up to options.max_expansion while phi keeps falling and
// the Armijo test holds; the objective ends at the best point, recorded in
// `result`. Not even alpha = 2 where the quadratic through phi0, the slope
// and phi(1) has its minimum at or before alpha = 5/4, that is phi(1) -
// phi0 >= 3/5 slope: a Newton step near its equilibrium (phi(1) - phi0 =
// slope / 2 on a quadratic), whose doubled trial, refused, would only cost
// a path point, an energy and the move back. On the quadratic, phi(2) >=
// phi(1) from a minimum at 3/2 down; the margin keeps doublings that the
// energy's departure from it rewards (scary_face's hardest deployment
// step took 3 at ratios 0.60 to 0.65: 33 iterations, 40 without them).
void expand_along_path(ObjectiveEvaluator& evaluator, const BacktrackingMerit& merit, double phi,
                       const DescentStepOptions& options, DescentStepResult& result) {
  if (!(phi - merit.phi0 < 0.6 * merit.slope)) return;
  Eigen::VectorXd best = evaluator.position();
  bool moved = false;
  for (double alpha = 2.0; alpha <= options.max_expansion; alpha *= 2.0) {
    Eigen::VectorXd trial;
    double energy = 0.0;
    try {
      trial = merit.path(alpha);
      energy = evaluator.energy_at(trial);
    } catch (const std::domain_error&) {
      break;
    }
    ++result.trials;
    const double trial_phi = merit.merit ? merit.merit(energy, trial) : energy;
    if (!std::isfinite(energy) || !(trial_phi < phi) ||
        !(trial_phi <= merit.phi0 + options.sufficient_decrease * alpha * merit.slope))
      break;
    best = std::move(trial);
    phi = trial_phi;
    moved = true;
    result.energy = energy;
    result.step_fraction = alpha;
  }
  if (moved || evaluator.position() != best) evaluator.move_to(best);
}

}  // namespace

DescentStepResult backtrack_on_energy(ObjectiveEvaluator& evaluator, const Eigen::VectorXd& q0,
                                      double e0, const Eigen::VectorXd& p,
                                      const BacktrackingMerit& merit,
                                      const DescentStepOptions& options) {
  DescentStepResult result;
  double alpha = 1.0;
  for (int k = 0; k <= options.max_backtracks; ++k, alpha *= options.shrink) {
    if (q0 + alpha * p == q0) break;  // the step vanished in round-off
    ++result.trials;
    double energy = 0.0;
    Eigen::VectorXd trial;
    try {
      trial = merit.path ? merit.path(alpha) : Eigen::VectorXd(q0 + alpha * p);
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
    const bool endgame = std::abs(energy - e0) <= options.endgame_energy_change * std::abs(e0);
    const bool accepted =
        phi <= merit.phi0 + options.sufficient_decrease * alpha * merit.slope + slack ||
        (k == 0 && endgame && merit.progress && merit.progress());
    if (accepted) {
      result.accepted = true;
      result.step_fraction = alpha;
      result.energy = energy;
      if (k == 0 && merit.path && !endgame)
        expand_along_path(evaluator, merit, phi, options, result);
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
