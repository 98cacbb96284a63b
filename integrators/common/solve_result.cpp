#include "integrators/common/solve_result.hpp"

#include <cstdio>

namespace xshell {

namespace {

struct StatusText {
  const char* name;   // summary.json's
  const char* words;  // for messages
};

StatusText text(SolveStatus status) {
  switch (status) {
    case SolveStatus::Converged:
      return {"converged", "converged"};
    case SolveStatus::IterationLimit:
      return {"max_iterations", "maximum number of iterations reached"};
    case SolveStatus::LinearSolverFailed:
      return {"linear_solver_failed", "linear solver failed"};
    case SolveStatus::LineSearchFailed:
      return {"line_search_failed", "line search failed"};
    case SolveStatus::IntegratorFailed:
      return {"integrator_failed", "integrator failed"};
    case SolveStatus::InvalidConfiguration:
      return {"invalid_configuration", "invalid configurations"};
    case SolveStatus::NonFinite:
      return {"non_finite", "non-finite values"};
    case SolveStatus::Interrupted:
      return {"interrupted", "interrupted"};
    case SolveStatus::StepFailed:
      return {"step_failed", "step failed"};
    case SolveStatus::Diverged:
      return {"diverged", "diverging"};
  }
  return {"unknown", "unknown"};
}

}  // namespace

const char* to_string(SolveStatus status) { return text(status).name; }

const char* describe(SolveStatus status) { return text(status).words; }

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

void set_no_unknowns(double energy, SolveResult& result) {
  result.status = SolveStatus::Converged;
  result.reason = "no free unknowns";
  result.energy = energy;
  result.stable = true;
}

bool stop_or_limit(const std::atomic<bool>* stop, long iterations, long limit, const char* unit,
                   SolveResult& result) {
  if (stop != nullptr && stop->load()) {
    result.status = SolveStatus::Interrupted;
    result.reason = "stop flag raised";
    return true;
  }
  if (iterations >= limit) {
    result.status = SolveStatus::IterationLimit;
    result.reason = "no convergence in " + std::to_string(iterations) + " " + unit;
    return true;
  }
  return false;
}

}  // namespace xshell
