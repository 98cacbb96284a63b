// The tests before every Newton iteration, plain (newton.hpp) or
// constrained (constrained_newton.hpp), in this order:
//   1. the energy or the gradient measure not finite  -> NonFinite
//   2. the solver's convergence test passed            -> Converged
//   3. the iterations stagnated (round-off floor)      -> LineSearchFailed
//   4. the stop flag raised                            -> Interrupted
//   5. the iteration limit reached                     -> IterationLimit
#pragma once

#include <atomic>
#include <string>

#include "integrators/common/solve_result.hpp"

namespace xshell {

// The state before the next iteration.
struct IterationCheck {
  long iterations = 0;  // iterations done
  double energy = 0.0;
  double gradient_measure = 0.0;
  bool converged = false;  // the solver's convergence test passed
  // Why the iterations stagnated ("the step fell below the scaled step
  // tolerance", ...), or empty when they did not.
  std::string stagnation;
};

// Records the state in `result` (iterations, energy, gradient measure) and
// returns true, with result's status and reason set, when the solve must
// end before another iteration.
bool iteration_finished(const IterationCheck& check, const std::atomic<bool>* stop,
                        long max_iterations, SolveResult& result);

}  // namespace xshell
