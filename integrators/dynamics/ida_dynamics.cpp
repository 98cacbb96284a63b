#include "integrators/dynamics/ida_dynamics.hpp"

#include "integrators/common/wall_clock.hpp"
#include "integrators/dynamics/ida_dynamics_run.hpp"

namespace xshell {

DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options,
                              const DynamicsCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  if (objective.size() == 0) {
    DynamicsResult result;
    set_no_unknowns(objective.energy(), result);
    return result;
  }
  DynamicsRun run(objective, options, callbacks, start);
  return run.solve();
}

}  // namespace xshell
