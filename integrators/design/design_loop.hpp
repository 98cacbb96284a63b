// The inverse design's optimization (docs/model.md section 9.7): the
// segment rest lengths p that minimize the design objective J(p)
// (design_objective.hpp) within relative bounds around the start's,
//   p0_s (1 - b) <= p_s <= p0_s (1 + b),
// by IPOPT with a limited-memory Hessian (optimization/bounded_minimizer.hpp).
// Each evaluation re-solves the equilibria from the last accepted ones; a
// design whose equilibrium fails is rejected by the line search.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "integrators/design/design_objective.hpp"
#include "integrators/optimization/bounded_minimizer.hpp"

namespace xshell {

struct DesignIteration {
  int iteration = 0;           // 0: the start
  double objective = 0.0;      // J
  DesignTerms terms;           // J's terms (unweighted) at the iterate
  double optimality = 0.0;     // IPOPT's dual infeasibility (scaled)
  int evaluations = 0;         // evaluations of J so far
  int failed_evaluations = 0;  // of them, designs whose equilibria failed
  double seconds = 0.0;        // since the start of the optimization
};

struct DesignLoopOptions {
  double max_relative_change = 0.2;  // b, in (0, 1)
  int max_iterations = 100;
  double tolerance = 1e-8;  // IPOPT's tol
  std::function<void(const DesignIteration&)> on_iteration;
  const std::atomic<bool>* stop = nullptr;
};

struct DesignLoopResult {
  MinimizerStatus status = MinimizerStatus::Failed;
  std::string reason;
  std::vector<double> lengths;  // the best design found (the start when none)
  DesignEvaluation final;       // J at `lengths`, the equilibria left there
  std::vector<DesignIteration> history;
  int iterations = 0, evaluations = 0, failed_evaluations = 0;
};

// Throws std::invalid_argument for a bound outside (0, 1).
DesignLoopResult optimize_design(DesignObjective& objective, const DesignLoopOptions& options);

}  // namespace xshell
