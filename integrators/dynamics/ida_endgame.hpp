// The end game of solve_dynamics: once the motion has died out and the
// Hessian is positive definite, the remaining steps are taken with infinite
// length. Backward Euler with an infinite step is a Newton step, so they
// are Newton iterations with the energy line search (newton.hpp), which
// only lower the energy, from the objective's current state.
#pragma once

#include <string>

#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/newton/newton.hpp"

namespace xshell {

// At most max_iterations Newton iterations, each reported through
// callbacks.on_step as a step of order 0 at rest, numbered after
// steps_before; `report` carries the other fields (time, step size).
NewtonResult run_endgame(Objective& objective, const DynamicsOptions& options, int max_iterations,
                         const DynamicsCallbacks& callbacks, long steps_before,
                         DynamicsReport& report);

// The run's status and reason after an end game that ended the run: the end
// game's status when it converged, was interrupted or met non-finite
// values, else IntegratorFailed.
SolveStatus endgame_status(const NewtonResult& polished);
std::string endgame_reason(const NewtonResult& polished);

}  // namespace xshell
