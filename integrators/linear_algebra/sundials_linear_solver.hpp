// A SUNLinearSolver of type DIRECT whose setup and solve are C++ objects.
//
// KINSOL and IDA hand their Newton systems J x = b to a SUNLinearSolver:
// setup(A) once per Jacobian update, solve(A, x, b) per Newton iteration.
// The adapter ignores A (a placeholder matrix, see make_placeholder_matrix):
// the backend assembles and factorizes its own operator from the model, for
// example a Hessian with CHOLMOD.
//
// Return codes follow SUNDIALS: 0 success, > 0 recoverable failure (the
// integrator may retry with a fresh Jacobian or a smaller step), < 0
// unrecoverable. C++ exceptions never cross the C boundary: the adapter
// catches them and returns SUNLS_PACKAGE_FAIL_UNREC.
#pragma once

#include "integrators/linear_algebra/sundials_handles.hpp"

namespace xshell {

class DirectSolveBackend {
 public:
  virtual ~DirectSolveBackend() = default;
  // Builds and factorizes the operator at the integrator's current state.
  // Returns SUNLS_SUCCESS, SUNLS_PACKAGE_FAIL_REC (e.g. not positive
  // definite) or SUNLS_PACKAGE_FAIL_UNREC.
  virtual int setup() = 0;
  // x = J^-1 b; b, x: the integrator's system size. Same return codes.
  virtual int solve(const double* b, double* x) = 0;
};

// A linear solver calling `backend` (borrowed: it must outlive the solver).
SunLinearSolver make_direct_linear_solver(SUNContext context, DirectSolveBackend& backend);

}  // namespace xshell
