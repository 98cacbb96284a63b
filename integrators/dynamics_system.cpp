#include "dynamics_system.hpp"

#include <sundials/sundials_linearsolver.h>

namespace xshell {

DynamicsSystem::DynamicsSystem(ObjectiveEvaluator& evaluator, DynamicsForm form,
                               Eigen::VectorXd mass, double damping)
    : evaluator_(evaluator), form_(form), mass_(std::move(mass)), damping_(damping) {}

int DynamicsSystem::residual(realtype, N_Vector y, N_Vector yp, N_Vector r, void* user_data) {
  auto& self = *static_cast<DynamicsSystem*>(user_data);
  const Eigen::Index n = self.unknowns();
  const double* Y = N_VGetArrayPointer(y);
  const double* YP = N_VGetArrayPointer(yp);
  double* R = N_VGetArrayPointer(r);
  // The gradient lands in the last n entries of r, then the rest is added.
  double* g = self.form_ == DynamicsForm::SecondOrder ? R + n : R;
  const int status = self.evaluator_.gradient_at(Y, g);
  if (status != 0) return status;
  const Eigen::Map<const Eigen::VectorXd> m(self.mass_.data(), n);
  const double c = self.damping_;
  if (self.form_ == DynamicsForm::SecondOrder) {
    const Eigen::Map<const Eigen::VectorXd> v(Y + n, n), qp(YP, n), vp(YP + n, n);
    Eigen::Map<Eigen::VectorXd>(R, n) = qp - v;
    Eigen::Map<Eigen::VectorXd>(R + n, n) += m.cwiseProduct(vp + c * v);
  } else {
    const Eigen::Map<const Eigen::VectorXd> qp(YP, n);
    Eigen::Map<Eigen::VectorXd>(R, n) += c * m.cwiseProduct(qp);
  }
  return 0;
}

int DynamicsSystem::jacobian(realtype, realtype c_j, N_Vector y, N_Vector, N_Vector, SUNMatrix,
                             void* user_data, N_Vector, N_Vector, N_Vector) {
  auto& self = *static_cast<DynamicsSystem*>(user_data);
  self.cj_ = c_j;
  return self.evaluator_.move_to(N_VGetArrayPointer(y));
}

int DynamicsSystem::setup() {
  setup_failed_ = true;
  const double c = damping_, cj = cj_;
  const double coefficient = form_ == DynamicsForm::SecondOrder ? cj * cj + c * cj : c * cj;
  const Eigen::VectorXd shift = coefficient * mass_;
  FactorizationStatus status;
  try {
    status = cholesky_.factorize(evaluator_.objective().hessian(), &shift);
  } catch (...) {
    const int code = evaluator_.fail_with_current_exception();
    return code > 0 ? SUNLS_PACKAGE_FAIL_REC : SUNLS_PACKAGE_FAIL_UNREC;
  }
  if (status == FactorizationStatus::NonFinite) {
    evaluator_.record(EvaluationFailure::NonFinite, "the Hessian is not finite");
    return SUNLS_PACKAGE_FAIL_REC;
  }
  if (status == FactorizationStatus::NotPositiveDefinite) return SUNLS_PACKAGE_FAIL_REC;
  setup_cj_ = cj;
  setup_failed_ = false;
  return SUNLS_SUCCESS;
}

int DynamicsSystem::solve(const double* b, double* x) {
  const Eigen::Index n = unknowns();
  if (form_ == DynamicsForm::FirstOrder) {
    cholesky_.solve(b, x);
  } else {
    // Schur complement of the 2n system (see the header), with the c_j the
    // factorization was made for; IDA rescales for a changed c_j itself.
    const double cj = setup_cj_, c = damping_;
    const Eigen::Map<const Eigen::VectorXd> b1(b, n), b2(b + n, n);
    const Eigen::VectorXd rhs = b2 + (cj + c) * mass_.cwiseProduct(b1);
    Eigen::Map<Eigen::VectorXd> dq(x, n), dv(x + n, n);
    const Eigen::VectorXd b1_copy = b1;  // b and x may alias
    cholesky_.solve(rhs.data(), dq.data());
    dv = cj * dq - b1_copy;
  }
  const Eigen::Map<const Eigen::VectorXd> solution(x, size());
  return solution.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

Eigen::VectorXd DynamicsSystem::consistent_derivatives(const Eigen::VectorXd& y) {
  const Eigen::Index n = unknowns();
  const Eigen::VectorXd& g = evaluator_.gradient();
  Eigen::VectorXd yp(size());
  if (form_ == DynamicsForm::SecondOrder) {
    const Eigen::VectorXd v = y.tail(n);
    yp.head(n) = v;
    yp.tail(n) = -damping_ * v - g.cwiseQuotient(mass_);
  } else {
    yp = -g.cwiseQuotient(mass_) / damping_;
  }
  return yp;
}

}  // namespace xshell
