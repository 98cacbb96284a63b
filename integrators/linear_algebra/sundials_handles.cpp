#include "integrators/linear_algebra/sundials_handles.hpp"

#include <cstdlib>
#include <new>
#include <stdexcept>
#include <string>

namespace xshell {

SunContext::SunContext() {
  if (SUNContext_Create(nullptr, &context_) != 0 || context_ == nullptr)
    throw std::runtime_error("SUNContext_Create failed");
}

SunContext::~SunContext() { SUNContext_Free(&context_); }

NVector make_serial_vector(Eigen::Index size, SUNContext context) {
  NVector v(N_VNew_Serial(static_cast<sunindextype>(size), context));
  if (!v) throw std::bad_alloc();
  N_VConst(0.0, v.get());
  return v;
}

Eigen::Map<Eigen::VectorXd> as_eigen(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

namespace {

SUNMatrix_ID placeholder_id(SUNMatrix) { return SUNMATRIX_CUSTOM; }
int placeholder_zero(SUNMatrix) { return 0; }
void placeholder_destroy(SUNMatrix A) { SUNMatFreeEmpty(A); }

}  // namespace

SunMatrix make_placeholder_matrix(SUNContext context) {
  SunMatrix A(SUNMatNewEmpty(context));
  if (!A) throw std::bad_alloc();
  A->content = nullptr;
  A->ops->getid = placeholder_id;
  A->ops->zero = placeholder_zero;
  A->ops->destroy = placeholder_destroy;
  return A;
}

void keep_sundials_message(int, const char* module, const char* function, char* message,
                           void* user_data) {
  auto& last = *static_cast<std::string*>(user_data);
  last = std::string(module ? module : "") + "/" + (function ? function : "") + ": " +
         (message ? message : "");
}

namespace {

std::string take_string(char* text) {
  std::string copy = text != nullptr ? text : "unknown flag";
  std::free(text);
  return copy;
}

}  // namespace

std::string kinsol_flag_name(int flag) { return take_string(KINGetReturnFlagName(flag)); }

std::string ida_flag_name(int flag) { return take_string(IDAGetReturnFlagName(flag)); }

void check_sundials(int flag, const char* what) {
  if (flag < 0)
    throw std::runtime_error(std::string(what) + " failed with flag " + std::to_string(flag));
}

}  // namespace xshell
