#include "integrators/dynamics/ida_dynamics.hpp"

#include "integrators/common/wall_clock.hpp"
#include "integrators/dynamics/ida_dynamics_run.hpp"

namespace xshell {

DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options,
                              const DynamicsCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  if (objective.size() == 0) {
    DynamicsResult result;
    result.status = SolveStatus::Converged;
    result.reason = "no free unknowns";
    result.energy = objective.energy();
    result.stable = true;
    return result;
  }
  DynamicsRun run(objective, options, callbacks, start);
  return run.solve();
}

}  // namespace xshell
