#include "integrators/newton/iteration_checks.hpp"

#include <cmath>

namespace xshell {

bool iteration_finished(const IterationCheck& check, const std::atomic<bool>* stop,
                        long max_iterations, SolveResult& result) {
  result.iterations = check.iterations;
  result.energy = check.energy;
  result.gradient_measure = check.gradient_measure;
  if (!std::isfinite(check.energy) || !std::isfinite(check.gradient_measure)) {
    result.status = SolveStatus::NonFinite;
    result.reason =
        "energy or gradient not finite after " + std::to_string(check.iterations) + " iterations";
    return true;
  }
  if (check.converged) {
    result.status = SolveStatus::Converged;
    result.reason = "gradient measure " + scientific(check.gradient_measure) + " <= tolerance";
    return true;
  }
  if (!check.stagnation.empty()) {
    result.status = SolveStatus::LineSearchFailed;
    result.reason = "stagnation: " + check.stagnation + " at gradient measure " +
                    scientific(check.gradient_measure) + " (round-off floor above the tolerance?)";
    return true;
  }
  return stop_or_limit(stop, check.iterations, max_iterations, "iterations", result);
}

}  // namespace xshell
