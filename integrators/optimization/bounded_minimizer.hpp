// Minimization of a smooth function under bounds on its variables,
//   min f(p)  subject to  lower <= p <= upper,
// by IPOPT's interior-point method with a limited-memory quasi-Newton
// Hessian (ipopt_minimizer.cpp). It calls `evaluate` for f and its gradient
// (both at once: the inverse design's objective computes them together by
// one equilibrium solve and its adjoint). An evaluation that fails (returns false: for example an
// equilibrium that could not be solved) is rejected by IPOPT's line search,
// which shortens the step; it only ends the run at the starting point.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <string>

namespace xshell {

struct BoundedProblem {
  Eigen::VectorXd start, lower, upper;  // same size; lower <= start <= upper
  // f(p) and its gradient (resized by the callee); false when p cannot be
  // evaluated.
  std::function<bool(const Eigen::VectorXd& p, double& f, Eigen::VectorXd& gradient)> evaluate;
};

struct MinimizerIteration {
  int iteration = 0;                // 0: the starting point
  double objective = 0.0;           // f at the iterate
  double dual_infeasibility = 0.0;  // the optimality measure (projected gradient, scaled)
  double step_norm = 0.0;           // max-norm of the last step (0 at iteration 0)
  int evaluations = 0;              // calls of `evaluate` so far
};

struct MinimizerOptions {
  int max_iterations = 100;
  double tolerance = 1e-8;             // IPOPT's `tol` (relative, on the scaled problem)
  double acceptable_tolerance = 1e-6;  // IPOPT's `acceptable_tol`
  int history = 6;                     // limited-memory pairs kept
  std::function<void(const MinimizerIteration&)> on_iteration;  // once per iteration
  const std::atomic<bool>* stop = nullptr;                      // checked once per iteration
};

enum class MinimizerStatus { Converged, IterationLimit, Interrupted, Failed };

struct MinimizerResult {
  MinimizerStatus status = MinimizerStatus::Failed;
  std::string reason;      // IPOPT's status in words
  Eigen::VectorXd p;       // the last accepted iterate (the start when none was)
  double objective = 0.0;  // f(p)
  int iterations = 0;
  int evaluations = 0;
};

// Throws std::invalid_argument when the sizes differ, a bound is not
// ordered or the start lies outside the bounds.
MinimizerResult minimize_bounded(const BoundedProblem& problem,
                                 const MinimizerOptions& options = {});

const char* minimizer_status_name(MinimizerStatus status);

}  // namespace xshell
