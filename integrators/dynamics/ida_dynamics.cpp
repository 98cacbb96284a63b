#include "integrators/dynamics/ida_dynamics.hpp"

#include "integrators/common/wall_clock.hpp"
#include "integrators/dynamics/ida_dynamics_run.hpp"

namespace xshell {

const char* to_string(DynamicsStatus status) {
  switch (status) {
    case DynamicsStatus::Converged:
      return "converged";
    case DynamicsStatus::MaxSteps:
      return "maximum number of steps reached";
    case DynamicsStatus::LinearSolverFailed:
      return "linear solver failed";
    case DynamicsStatus::IntegratorFailed:
      return "integrator failed";
    case DynamicsStatus::NonFinite:
      return "non-finite values";
    case DynamicsStatus::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options,
                              const DynamicsCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  if (objective.size() == 0) {
    DynamicsResult result;
    result.status = DynamicsStatus::Converged;
    result.reason = "no free unknowns";
    result.energy = objective.energy();
    result.stable = true;
    return result;
  }
  DynamicsRun run(objective, options, callbacks, start);
  return run.solve();
}

}  // namespace xshell
