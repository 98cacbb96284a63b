#include "integrators/dynamics/ida_endgame.hpp"

namespace xshell {

NewtonResult run_endgame(Objective& objective, const DynamicsOptions& options, int max_iterations,
                         const DynamicsCallbacks& callbacks, long steps_before,
                         DynamicsReport& report) {
  NewtonOptions newton;
  newton.gradient_tolerance = options.stopping.gradient_tolerance;
  newton.max_iterations = max_iterations;
  newton.shift = options.shift;
  // A saddle is left by solve_dynamics itself (options.escape), which
  // integrates on from there: the end game only polishes.
  newton.escape.enabled = false;
  NewtonCallbacks forward;
  forward.stop = callbacks.stop;
  forward.on_iteration = [&](const NewtonReport& r) {
    if (r.iteration == 0) return;  // the state IDA ended in, reported already
    report.step = steps_before + r.iteration;
    report.order = 0;
    report.energy = r.energy;
    report.kinetic_energy = 0.0;
    report.gradient_measure = r.gradient_measure;
    if (callbacks.on_step) callbacks.on_step(report);
  };
  return solve_newton(objective, newton, forward);
}

SolveStatus endgame_status(const NewtonResult& polished) {
  switch (polished.status) {
    case SolveStatus::Converged:
    case SolveStatus::Interrupted:
    case SolveStatus::NonFinite:
      return polished.status;
    default:
      return SolveStatus::IntegratorFailed;
  }
}

std::string endgame_reason(const NewtonResult& polished) {
  switch (polished.status) {
    case SolveStatus::Converged:
      return "gradient below tolerance, at rest (end game: " + std::to_string(polished.iterations) +
             " steps of infinite length)";
    case SolveStatus::Interrupted:
      return "stop flag raised";
    default:
      return "end game: " + polished.reason;
  }
}

}  // namespace xshell
