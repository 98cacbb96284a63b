#include "integrators/newton/kinsol_system.hpp"

#include <sundials/sundials_linearsolver.h>

#include <algorithm>

#include "integrators/common/wall_clock.hpp"

namespace xshell {

NewtonSystem::NewtonSystem(ObjectiveEvaluator& evaluator, const ShiftOptions& shift)
    : evaluator_(evaluator), shift_options_(shift) {}

int NewtonSystem::residual(N_Vector u, N_Vector f, void* user_data) {
  auto& self = *static_cast<NewtonSystem*>(user_data);
  return self.evaluator_.gradient_at(N_VGetArrayPointer(u), N_VGetArrayPointer(f));
}

int NewtonSystem::jacobian(N_Vector u, N_Vector, SUNMatrix, void* user_data, N_Vector, N_Vector) {
  auto& self = *static_cast<NewtonSystem*>(user_data);
  return self.evaluator_.move_to(N_VGetArrayPointer(u));
}

void NewtonSystem::prepare_hessian() {
  const Clock::time_point start = Clock::now();
  try {
    evaluator_.objective().hessian();
  } catch (...) {
    // setup() asks again and reports the failure.
  }
  hessian_seconds_ += seconds_since(start);
}

int NewtonSystem::setup() {
  try {
    const Clock::time_point start = Clock::now();
    const Eigen::SparseMatrix<double>& H = evaluator_.objective().hessian();
    hessian_seconds_ += seconds_since(start);
    const Clock::time_point assembled = Clock::now();
    last_ = factorize_with_shift(cholesky_, H, mass_, shift_options_);
    factorization_seconds_ += seconds_since(assembled);
  } catch (...) {
    setup_failed_ = true;
    const int code = evaluator_.fail_with_current_exception();
    return code > 0 ? SUNLS_PACKAGE_FAIL_REC : SUNLS_PACKAGE_FAIL_UNREC;
  }
  if (last_.shifted) {
    any_shift_ = true;
    max_shift_ = std::max(max_shift_, last_.shift);
  }
  switch (last_.status) {
    case FactorizationStatus::PositiveDefinite:
      if (deferral_ == Deferral::Always || (last_.shifted && deferral_ == Deferral::ShiftedSteps)) {
        deferred_ = true;
        return SUNLS_PACKAGE_FAIL_REC;
      }
      return SUNLS_SUCCESS;
    case FactorizationStatus::NonFinite:
      evaluator_.record(EvaluationFailure::NonFinite, "the Hessian is not finite");
      break;
    case FactorizationStatus::NotPositiveDefinite:
      break;
  }
  // Recoverable by convention (KINSOL stops at a failed setup either way,
  // with KIN_LSETUP_FAIL, and the driver reports the reason).
  setup_failed_ = true;
  return SUNLS_PACKAGE_FAIL_REC;
}

int NewtonSystem::solve(const double* b, double* x) {
  cholesky_.solve(b, x);
  const Eigen::Map<const Eigen::VectorXd> step(x, evaluator_.size());
  return step.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

}  // namespace xshell
