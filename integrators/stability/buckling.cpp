#include "integrators/stability/buckling.hpp"

#include <Spectra/SymGEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>

#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

namespace {

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
    if (!largest_softening(K0, KL, options, solver, nu, phi)) return out;
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
    case BucklingStatus::TimeLimit:
      return kTimeLimit;
  }
  return "unknown";
}

}  // namespace xshell
