#include "integrators/dynamics/ida_system.hpp"

#include <sundials/sundials_linearsolver.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace xshell {

namespace {

bool same_pattern(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B) {
  if (A.rows() != B.rows() || A.cols() != B.cols() || A.nonZeros() != B.nonZeros() ||
      !A.isCompressed() || !B.isCompressed())
    return false;
  return std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, B.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), B.innerIndexPtr());
}

// out += s B (in place when the patterns agree).
void accumulate(Eigen::SparseMatrix<double>& out, double s, const Eigen::SparseMatrix<double>& B) {
  if (s == 0.0) return;
  if (same_pattern(out, B)) {
    Eigen::Map<Eigen::VectorXd>(out.valuePtr(), out.nonZeros()) +=
        s * Eigen::Map<const Eigen::VectorXd>(B.valuePtr(), B.nonZeros());
  } else {
    Eigen::SparseMatrix<double> sum = out + s * B;
    sum.makeCompressed();
    out = std::move(sum);
  }
}

void check(const Damping& d, Eigen::Index n) {
  if (d.stiffness_coefficient > 0.0 && (d.stiffness.rows() != n || d.stiffness.cols() != n))
    throw std::invalid_argument("DynamicsSystem: damping stiffness of the wrong size");
}

}  // namespace

DynamicsSystem::DynamicsSystem(ObjectiveEvaluator& evaluator, DynamicsForm form,
                               Eigen::VectorXd mass, Damping damping)
    : evaluator_(evaluator), form_(form), mass_(std::move(mass)) {
  set_damping(std::move(damping));
}

void DynamicsSystem::set_damping(Damping damping) {
  check(damping, unknowns());
  from_ = std::move(damping);
  from_.stiffness.makeCompressed();
  blending_ = false;
}

void DynamicsSystem::blend_damping(Damping target, double start, double duration) {
  check(target, unknowns());
  if (blending_) update_blend(std::numeric_limits<double>::infinity());
  to_ = std::move(target);
  to_.stiffness.makeCompressed();
  blending_ = true;
  blend_start_ = start;
  blend_end_ = start + std::max(duration, 0.0);
}

bool DynamicsSystem::update_blend(double t) {
  if (blending_ && t >= blend_end_) {
    from_ = std::move(to_);
    to_ = Damping();
    blending_ = false;
  }
  return blending_;
}

double DynamicsSystem::weight(double t) const {
  if (!blending_) return 0.0;
  if (t >= blend_end_) return 1.0;
  if (t <= blend_start_) return 0.0;
  const double x = (t - blend_start_) / (blend_end_ - blend_start_);
  return x * x * (3.0 - 2.0 * x);
}

double DynamicsSystem::mass_coefficient(double t) const {
  const double w = weight(t);
  return (1.0 - w) * from_.mass_coefficient + w * (blending_ ? to_.mass_coefficient : 0.0);
}

void DynamicsSystem::add_stiffness(double t, double s, Eigen::SparseMatrix<double>& out) const {
  const double w = weight(t);
  if (from_.stiffness_coefficient > 0.0)
    accumulate(out, s * (1.0 - w) * from_.stiffness_coefficient, from_.stiffness);
  if (blending_ && to_.stiffness_coefficient > 0.0)
    accumulate(out, s * w * to_.stiffness_coefficient, to_.stiffness);
}

Eigen::VectorXd DynamicsSystem::damping_force(const Eigen::VectorXd& x, double t) const {
  const double w = weight(t);
  Eigen::VectorXd f = mass_coefficient(t) * mass_.cwiseProduct(x);
  // S x as S' x: S is symmetric, and the transposed product of a
  // column-major matrix is a dot product per column (a gather), cheaper
  // than the scatter of S x.
  if (from_.stiffness_coefficient > 0.0 && w < 1.0)
    f.noalias() += ((1.0 - w) * from_.stiffness_coefficient) * (from_.stiffness.transpose() * x);
  if (blending_ && to_.stiffness_coefficient > 0.0 && w > 0.0)
    f.noalias() += (w * to_.stiffness_coefficient) * (to_.stiffness.transpose() * x);
  return f;
}

int DynamicsSystem::residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* user_data) {
  auto& self = *static_cast<DynamicsSystem*>(user_data);
  const Eigen::Index n = self.unknowns();
  const double* Y = N_VGetArrayPointer(y);
  const double* YP = N_VGetArrayPointer(yp);
  double* R = N_VGetArrayPointer(r);
  // The gradient lands in the last n entries of r, then the rest is added.
  double* g = self.form_ == DynamicsForm::SecondOrder ? R + n : R;
  const int status = self.evaluator_.gradient_at(Y, g);
  if (status != 0) return status;
  if (self.form_ == DynamicsForm::SecondOrder) {
    const Eigen::Map<const Eigen::VectorXd> v(Y + n, n), qp(YP, n), vp(YP + n, n);
    Eigen::Map<Eigen::VectorXd>(R, n) = qp - v;
    Eigen::Map<Eigen::VectorXd>(R + n, n) += self.mass_.cwiseProduct(vp) + self.damping_force(v, t);
  } else {
    const Eigen::Map<const Eigen::VectorXd> qp(YP, n);
    Eigen::Map<Eigen::VectorXd>(R, n) += self.damping_force(qp, t);
  }
  return 0;
}

int DynamicsSystem::jacobian(realtype t, realtype c_j, N_Vector y, N_Vector, N_Vector, SUNMatrix,
                             void* user_data, N_Vector, N_Vector, N_Vector) {
  auto& self = *static_cast<DynamicsSystem*>(user_data);
  self.cj_ = c_j;
  self.jacobian_t_ = t;
  return self.evaluator_.move_to(N_VGetArrayPointer(y));
}

int DynamicsSystem::setup() {
  setup_failed_ = true;
  const double cj = cj_, t = jacobian_t_, a = mass_coefficient(t);
  const double shift_coefficient = form_ == DynamicsForm::SecondOrder ? cj * cj + a * cj : a * cj;
  const Eigen::VectorXd shift = shift_coefficient * mass_;
  FactorizationStatus status;
  try {
    const Eigen::SparseMatrix<double>& H = evaluator_.objective().hessian();
    const bool stiffness =
        from_.stiffness_coefficient > 0.0 || (blending_ && to_.stiffness_coefficient > 0.0);
    if (stiffness) {
      // K = H + c_j (stiffness part of C) + shift M.
      if (same_pattern(work_, H))
        Eigen::Map<Eigen::VectorXd>(work_.valuePtr(), work_.nonZeros()) =
            Eigen::Map<const Eigen::VectorXd>(H.valuePtr(), H.nonZeros());
      else
        work_ = H;
      add_stiffness(t, cj, work_);
      status = cholesky_.factorize(work_, &shift);
    } else {
      status = cholesky_.factorize(H, &shift);
    }
  } catch (...) {
    const int code = evaluator_.fail_with_current_exception();
    return code > 0 ? SUNLS_PACKAGE_FAIL_REC : SUNLS_PACKAGE_FAIL_UNREC;
  }
  if (status == FactorizationStatus::NonFinite) {
    evaluator_.record(EvaluationFailure::NonFinite, "the Hessian is not finite");
    return SUNLS_PACKAGE_FAIL_REC;
  }
  if (status == FactorizationStatus::NotPositiveDefinite) {
    if (on_indefinite_) on_indefinite_(cj);
    return SUNLS_PACKAGE_FAIL_REC;
  }
  setup_cj_ = cj;
  setup_t_ = t;
  setup_failed_ = false;
  return SUNLS_SUCCESS;
}

int DynamicsSystem::solve(const double* b, double* x) {
  const Eigen::Index n = unknowns();
  if (form_ == DynamicsForm::FirstOrder) {
    cholesky_.solve(b, x);
  } else {
    // Schur complement of the 2n system (see the header), with the c_j (and
    // C) the factorization was made for; IDA rescales for a changed c_j.
    const double cj = setup_cj_;
    const Eigen::Map<const Eigen::VectorXd> b1(b, n), b2(b + n, n);
    const Eigen::VectorXd b1_copy = b1;  // b and x may alias
    const Eigen::VectorXd rhs =
        b2 + cj * mass_.cwiseProduct(b1_copy) + damping_force(b1_copy, setup_t_);
    Eigen::Map<Eigen::VectorXd> dq(x, n), dv(x + n, n);
    cholesky_.solve(rhs.data(), dq.data());
    dv = cj * dq - b1_copy;
  }
  const Eigen::Map<const Eigen::VectorXd> solution(x, size());
  return solution.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

Eigen::VectorXd DynamicsSystem::consistent_derivatives(const Eigen::VectorXd& y, double t) {
  const Eigen::Index n = unknowns();
  const Eigen::VectorXd& g = evaluator_.gradient();
  Eigen::VectorXd yp(size());
  if (form_ == DynamicsForm::SecondOrder) {
    const Eigen::VectorXd v = y.tail(n);
    yp.head(n) = v;
    yp.tail(n) = -(damping_force(v, t) + g).cwiseQuotient(mass_);
    return yp;
  }
  return overdamped_velocity(t);
}

Eigen::VectorXd DynamicsSystem::overdamped_velocity(double t, double inertia) {
  const Eigen::Index n = unknowns();
  const Eigen::VectorXd& g = evaluator_.gradient();
  const bool stiffness =
      from_.stiffness_coefficient > 0.0 || (blending_ && to_.stiffness_coefficient > 0.0);
  if (!stiffness) return -g.cwiseQuotient(mass_) / (mass_coefficient(t) + inertia);
  // (C + inertia M) v = -g.
  Eigen::SparseMatrix<double> C(n, n);
  add_stiffness(t, 1.0, C);
  const Eigen::VectorXd shift = (mass_coefficient(t) + inertia) * mass_;
  if (cholesky_.factorize(C, &shift) != FactorizationStatus::PositiveDefinite)
    throw std::runtime_error("the damping matrix C is not positive definite");
  return -cholesky_.solve(Eigen::VectorXd(g));
}

}  // namespace xshell
