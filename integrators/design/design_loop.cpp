#include "design_loop.hpp"

#include <chrono>
#include <cmath>
#include <deque>
#include <stdexcept>

namespace xshell {

namespace {

struct Evaluated {
  double value = 0.0;
  DesignTerms terms;
};

// The evaluation IPOPT accepted as its iterate: the latest one with its
// objective value (IPOPT reports the value, not the point).
const Evaluated* accepted(const std::deque<Evaluated>& recent, double value) {
  for (auto it = recent.rbegin(); it != recent.rend(); ++it)
    if (std::abs(it->value - value) <= 1e-12 * std::max(1.0, std::abs(value))) return &*it;
  return nullptr;
}

}  // namespace

DesignLoopResult optimize_design(DesignObjective& objective, const DesignLoopOptions& options) {
  const double b = options.max_relative_change;
  if (!(b > 0.0 && b < 1.0))
    throw std::invalid_argument(
        "design: the largest relative change of a rest length must lie in "
        "(0, 1), got " +
        std::to_string(b));
  const auto clock_start = std::chrono::steady_clock::now();
  const std::vector<double>& p0 = objective.start_lengths();
  const Eigen::Map<const Eigen::VectorXd> start(p0.data(), p0.size());
  BoundedProblem problem;
  problem.start = start;
  problem.lower = (1.0 - b) * start;
  problem.upper = (1.0 + b) * start;
  DesignLoopResult result;
  std::deque<Evaluated> recent;
  problem.evaluate = [&](const Eigen::VectorXd& p, double& f, Eigen::VectorXd& gradient) {
    ++result.evaluations;
    const DesignEvaluation e =
        objective.evaluate(std::vector<double>(p.data(), p.data() + p.size()));
    if (e.status != DesignStatus::Ok) {
      ++result.failed_evaluations;
      return false;
    }
    f = e.value;
    gradient = e.gradient;
    recent.push_back({e.value, e.terms});
    if (recent.size() > 32) recent.pop_front();
    return true;
  };
  MinimizerOptions minimizer;
  minimizer.max_iterations = options.max_iterations;
  minimizer.tolerance = options.tolerance;
  minimizer.stop = options.stop;
  minimizer.on_iteration = [&](const MinimizerIteration& it) {
    DesignIteration d;
    d.iteration = it.iteration;
    d.objective = it.objective;
    if (const Evaluated* e = accepted(recent, it.objective)) d.terms = e->terms;
    d.optimality = it.dual_infeasibility;
    d.evaluations = result.evaluations;
    d.failed_evaluations = result.failed_evaluations;
    d.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
    result.history.push_back(d);
    if (options.on_iteration) options.on_iteration(d);
  };
  const MinimizerResult m = minimize_bounded(problem, minimizer);
  result.status = m.status;
  result.reason = m.reason;
  result.iterations = m.iterations;
  result.lengths.assign(m.p.data(), m.p.data() + m.p.size());
  // The equilibria at the result (the last evaluation may have been a
  // rejected trial point).
  result.final = objective.evaluate(result.lengths);
  return result;
}

}  // namespace xshell
