#include "integrators/linear_algebra/sundials_linear_solver.hpp"

#include <sundials/sundials_linearsolver.h>

#include <new>

namespace xshell {

namespace {

DirectSolveBackend& backend_of(SUNLinearSolver S) {
  return *static_cast<DirectSolveBackend*>(S->content);
}

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }

SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }

int initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }

int setup(SUNLinearSolver S, SUNMatrix) {
  try {
    return backend_of(S).setup();
  } catch (...) {
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
  try {
    return backend_of(S).solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
  } catch (...) {
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

int free_solver(SUNLinearSolver S) {
  if (S == nullptr) return SUNLS_SUCCESS;
  S->content = nullptr;  // borrowed
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

SunLinearSolver make_direct_linear_solver(SUNContext context, DirectSolveBackend& backend) {
  SunLinearSolver S(SUNLinSolNewEmpty(context));
  if (!S) throw std::bad_alloc();
  S->content = &backend;
  S->ops->gettype = get_type;
  S->ops->getid = get_id;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->free = free_solver;
  return S;
}

}  // namespace xshell
