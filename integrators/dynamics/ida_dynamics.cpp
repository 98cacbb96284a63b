#include "integrators/dynamics/ida_dynamics.hpp"

#include "integrators/common/wall_clock.hpp"
#include "integrators/dynamics/ida_dynamics_run.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

namespace {

// Adds a later run's counters (after an escape) to the result so far; the
// final state's values are the later run's.
void continue_with(const DynamicsResult& later, DynamicsResult& result) {
  DynamicsResult sum = later;
  sum.iterations += result.iterations;
  sum.factorizations += result.factorizations;
  sum.time += result.time;
  sum.residual_evaluations += result.residual_evaluations;
  sum.error_test_failures += result.error_test_failures;
  sum.convergence_failures += result.convergence_failures;
  sum.rebases += result.rebases;
  sum.refreshes += result.refreshes;
  sum.endgame_steps += result.endgame_steps;
  sum.endgame_fallbacks += result.endgame_fallbacks;
  sum.rejected_steps += result.rejected_steps;
  sum.saddles_escaped = result.saddles_escaped;
  result = std::move(sum);
}

}  // namespace

// Integrates; at a converged saddle (options.escape), moves off it along
// its lowest mode (saddle_escape.hpp) and integrates again from rest there,
// the reports numbered on from the previous run's.
DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options,
                              const DynamicsCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  DynamicsResult result;
  if (objective.size() == 0) {
    set_no_unknowns(objective.energy(), result);
    return result;
  }
  result = DynamicsRun(objective, options, callbacks, start).solve();
  CholeskySolver solver;
  DynamicsCallbacks later = callbacks;
  while (options.escape.enabled && result.converged() && !result.stable &&
         static_cast<int>(result.saddles_escaped.size()) < options.escape.max_escapes) {
    objective.rebase();
    const EscapeResult left =
        escape_saddle(objective, objective.hessian(), objective.mass(), solver, options.escape);
    if (left.outcome != EscapeOutcome::Escaped) break;
    result.saddles_escaped.push_back(left.saddle);
    const long steps = result.iterations + 1;  // the escape is a step
    const double time = result.time;
    if (callbacks.on_step)
      later.on_step = [&callbacks, steps, time](const DynamicsReport& r) {
        DynamicsReport shifted = r;
        shifted.step += steps;
        shifted.time += time;
        callbacks.on_step(shifted);
      };
    DynamicsOptions from_rest = options;
    from_rest.start.velocity = DynamicsStart::Rest;
    continue_with(DynamicsRun(objective, from_rest, later, start).solve(), result);
    result.iterations += 1;
  }
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace xshell
