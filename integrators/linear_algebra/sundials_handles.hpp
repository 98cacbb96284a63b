// RAII owners for the SUNDIALS 6 objects the solvers create: the context,
// serial vectors, matrices, linear solvers and the KINSOL / IDA memory.
//
// Destruction order matters only in one way: every object must be destroyed
// before the SunContext it was created with, which holds when the context is
// declared first (members are destroyed in reverse order of declaration).
#pragma once

#include <ida/ida.h>
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <Eigen/Core>
#include <memory>
#include <string>

namespace xshell {

// SUNContext_Create / SUNContext_Free.
class SunContext {
 public:
  SunContext();
  ~SunContext();
  SunContext(const SunContext&) = delete;
  SunContext& operator=(const SunContext&) = delete;

  operator SUNContext() const { return context_; }

 private:
  SUNContext context_ = nullptr;
};

struct NVectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
using NVector = std::unique_ptr<_generic_N_Vector, NVectorDeleter>;

struct SunMatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
using SunMatrix = std::unique_ptr<_generic_SUNMatrix, SunMatrixDeleter>;

struct SunLinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
using SunLinearSolver = std::unique_ptr<_generic_SUNLinearSolver, SunLinearSolverDeleter>;

struct KinsolDeleter {
  void operator()(void* memory) const { KINFree(&memory); }
};
using KinsolMemory = std::unique_ptr<void, KinsolDeleter>;

struct IdaDeleter {
  void operator()(void* memory) const { IDAFree(&memory); }
};
using IdaMemory = std::unique_ptr<void, IdaDeleter>;

// A serial vector of `size` entries (zeroed). Throws std::bad_alloc.
NVector make_serial_vector(Eigen::Index size, SUNContext context);

// The entries of a serial vector, viewed as an Eigen vector.
Eigen::Map<Eigen::VectorXd> as_eigen(N_Vector v);

// A matrix that stores nothing, for linear solvers that build their own
// operator: KINSOL and IDA require a non-null SUNMatrix with a DIRECT
// linear solver and zero it before every Jacobian evaluation, so it
// supports getid (SUNMATRIX_CUSTOM), zero (a no-op) and destroy only.
SunMatrix make_placeholder_matrix(SUNContext context);

// An error handler for KINSetErrHandlerFn / IDASetErrHandlerFn that prints
// nothing and keeps the last message in *user_data (a std::string): the
// drivers report failures through their results instead.
void keep_sundials_message(int error_code, const char* module, const char* function, char* message,
                           void* user_data);

// Names of KINSOL / IDA return flags (the C functions return malloc'ed
// strings that the caller must free; these copy and free them).
std::string kinsol_flag_name(int flag);
std::string ida_flag_name(int flag);

// Throws std::runtime_error naming `what` when a SUNDIALS call returned a
// negative flag (the convention for errors in all SUNDIALS packages).
void check_sundials(int flag, const char* what);

}  // namespace xshell
