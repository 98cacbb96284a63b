#include "integrators/stability/buckling.hpp"

#include <Spectra/SymGEigsShiftSolver.h>
#include <Spectra/SymGEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <stdexcept>

#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

namespace {

// Spectra's tolerance (1e-10) on lambda / (lambda - 1) resolves 1 / lambda
// to about that: 1e6 leaves four orders of magnitude above round-off.
constexpr double kLargestLoadFactor = 1e6;

// y = A x for a sparse symmetric A (both triangles stored).
class SparseProduct {
 public:
  using Scalar = double;
  SparseProduct(const Eigen::SparseMatrix<double>& A, const AnalysisDeadline& deadline)
      : A_(A), deadline_(deadline) {}
  Eigen::Index rows() const { return A_.rows(); }
  Eigen::Index cols() const { return A_.cols(); }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    deadline_.check();
    y.noalias() = A_ * x;
  }

 private:
  const Eigen::SparseMatrix<double>& A_;
  const AnalysisDeadline& deadline_;
};

// B = K_0: its product and, through a CHOLMOD factorization, its inverse.
class FactorizedMatrix {
 public:
  using Scalar = double;
  FactorizedMatrix(const Eigen::SparseMatrix<double>& B, CholeskySolver& solver)
      : B_(B), solver_(solver) {}
  Eigen::Index rows() const { return B_.rows(); }
  Eigen::Index cols() const { return B_.cols(); }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y.noalias() = B_ * x;
  }
  void solve(const double* x_in, double* y_out) const { solver_.solve(x_in, y_out); }

 private:
  const Eigen::SparseMatrix<double>& B_;
  CholeskySolver& solver_;
};

// (K0 - sigma (K0 - KL))^-1 for the buckling mode below, factorized at
// set_shift (K_L itself at sigma = 1), and its solves.
class ShiftedInverse {
 public:
  using Scalar = double;
  ShiftedInverse(const Eigen::SparseMatrix<double>& K0, const Eigen::SparseMatrix<double>& KL,
                 CholeskySolver& solver, const AnalysisDeadline& deadline)
      : K0_(K0), KL_(KL), solver_(solver), deadline_(deadline) {}
  Eigen::Index rows() const { return K0_.rows(); }
  Eigen::Index cols() const { return K0_.cols(); }
  void set_shift(double sigma) {
    const Eigen::SparseMatrix<double> shifted =
        sigma == 1.0 ? KL_ : (1.0 - sigma) * K0_ + sigma * KL_;
    if (solver_.factorize(shifted) != FactorizationStatus::PositiveDefinite)
      throw std::domain_error("the shifted stiffness is not positive definite");
  }
  void perform_op(const double* x_in, double* y_out) const {
    deadline_.check();
    solver_.solve(x_in, y_out);
  }

 private:
  const Eigen::SparseMatrix<double>& K0_;
  const Eigen::SparseMatrix<double>& KL_;
  CholeskySolver& solver_;
  const AnalysisDeadline& deadline_;
};

// The smallest load factor lambda > 1 of K0 phi = lambda (K0 - KL) phi, by
// Lanczos on (K_L)^-1 K0 (Spectra's buckling mode, shift 1: the loads as
// they are). Its spectrum is lambda / (lambda - 1): the loads' unaffected
// modes gather at 1, stiffened ones below, and the wanted one above, apart
// from the rest by 1 / (lambda - 1); in the regular-inverse form below
// the wanted nu = 1 / lambda sits next to the unaffected modes at 0 while
// the stiffened ones spread far below, and Lanczos crept (manta_ray
// deployed under gravity: 1000 restarts, 18 s, not converged). False when
// K_L is not positive definite or the eigensolver failed; lambda 0 when
// no lambda > 1 exists. Throws DeadlinePassed.
bool smallest_load_factor(const Eigen::SparseMatrix<double>& K0,
                          const Eigen::SparseMatrix<double>& KL, const BucklingOptions& options,
                          CholeskySolver& solver, double& lambda, Eigen::VectorXd& phi) {
  const int n = static_cast<int>(K0.rows());
  ShiftedInverse op(K0, KL, solver, options.deadline);
  SparseProduct b(K0, options.deadline);
  const int ncv = std::min(n, 20);
  try {
    Spectra::SymGEigsShiftSolver<ShiftedInverse, SparseProduct, Spectra::GEigsMode::Buckling> eigs(
        op, b, 1, ncv, 1.0);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, options.max_restarts, options.tolerance);
    if (eigs.info() != Spectra::CompInfo::Successful) return false;
    lambda = eigs.eigenvalues()(0);
    phi = eigs.eigenvectors().col(0);
  } catch (const std::domain_error&) {  // K_L is not positive definite
    return false;
  }
  // The loads' unaffected modes (lambda infinite) sit at 1 + round-off:
  // a factor beyond kLargestLoadFactor is one of them, not a buckling load.
  if (!(lambda > 1.0 && lambda < kLargestLoadFactor)) lambda = 0.0;
  return true;
}

// The largest nu of (K0 - KL) phi = nu K0 phi, K0 factorized in `solver`;
// false when the eigensolver failed. Throws DeadlinePassed.
bool largest_softening(const Eigen::SparseMatrix<double>& K0, const Eigen::SparseMatrix<double>& KL,
                       const BucklingOptions& options, CholeskySolver& solver, double& nu,
                       Eigen::VectorXd& phi) {
  const int n = static_cast<int>(K0.rows());
  const Eigen::SparseMatrix<double> softening = K0 - KL;
  if (n <= 40) {
    // Too small for Lanczos: dense generalized eigenproblem.
    const Eigen::MatrixXd a = softening, b = K0;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(a, b);
    if (dense.info() != Eigen::Success) return false;
    nu = dense.eigenvalues()(n - 1);
    phi = dense.eigenvectors().col(n - 1);
    return true;
  }
  SparseProduct a(softening, options.deadline);
  FactorizedMatrix b(K0, solver);
  const int ncv = std::min(n, 20);
  Spectra::SymGEigsSolver<SparseProduct, FactorizedMatrix, Spectra::GEigsMode::RegularInverse> eigs(
      a, b, 1, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, options.max_restarts, options.tolerance);
  if (eigs.info() != Spectra::CompInfo::Successful) return false;
  nu = eigs.eigenvalues()(0);
  phi = eigs.eigenvectors().col(0);
  return true;
}

}  // namespace

BucklingResult linearized_buckling(const Eigen::SparseMatrix<double>& K0,
                                   const Eigen::SparseMatrix<double>& KL,
                                   const BucklingOptions& options, CholeskySolver* reused) {
  BucklingResult out;
  const int n = static_cast<int>(K0.rows());
  CholeskySolver own;
  CholeskySolver& solver = reused ? *reused : own;
  if (n == 0 || solver.factorize(K0) != FactorizationStatus::PositiveDefinite) {
    out.status = BucklingStatus::UnloadedUnstable;
    return out;
  }
  double nu = 0.0;
  Eigen::VectorXd phi;
  try {
    double lambda = 0.0;
    if (n > 40 && smallest_load_factor(K0, KL, options, solver, lambda, phi)) {
      nu = lambda > 0.0 ? 1.0 / lambda : 0.0;
    } else {
      // K_L indefinite, or no convergence: the regular-inverse form.
      if (n > 40 && solver.factorize(K0) != FactorizationStatus::PositiveDefinite) return out;
      if (!largest_softening(K0, KL, options, solver, nu, phi)) return out;
    }
  } catch (const DeadlinePassed&) {
    out.status = BucklingStatus::TimeLimit;
    return out;
  }
  if (!(nu > 0.0)) {
    out.status = BucklingStatus::NoBuckling;
    return out;
  }
  out.status = BucklingStatus::Found;
  out.load_factor = 1.0 / nu;
  out.mode = phi;
  return out;
}

const char* buckling_status_name(BucklingStatus status) {
  switch (status) {
    case BucklingStatus::Found:
      return "found";
    case BucklingStatus::NoBuckling:
      return "no_buckling";
    case BucklingStatus::UnloadedUnstable:
      return "unloaded_unstable";
    case BucklingStatus::NotConverged:
      return "not_converged";
    case BucklingStatus::Refuted:
      return "refuted";
    case BucklingStatus::TimeLimit:
      return kTimeLimit;
  }
  return "unknown";
}

}  // namespace xshell
