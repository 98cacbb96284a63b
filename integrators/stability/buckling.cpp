#include "integrators/stability/buckling.hpp"

#include <Spectra/SymEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

namespace {

// Spectra's tolerance (1e-10) on lambda / (lambda - 1) resolves 1 / lambda
// to about that: 1e6 leaves four orders of magnitude above round-off.
constexpr double kLargestLoadFactor = 1e6;

// y = G^-1 P S P^T G^-T x, with P A P^T = G G^T factorized in `solver`
// (CholeskySolver::solve_lower/upper): the standard symmetric form of
// S phi = mu A phi, whose eigenvectors x give phi = P^T G^-T x. Lanczos
// then orthogonalizes in the plain inner product; in the generalized
// (B-inner product) modes every reorthogonalization pass costs a product
// with the stiffness, whose condition makes each pass fail its round-off
// test: 13 products per operation, most of the buckling's time on
// manta_ray (272 products for 21 operations).
class StandardForm {
 public:
  using Scalar = double;
  StandardForm(const Eigen::SparseMatrix<double>& S, CholeskySolver& solver,
               const AnalysisDeadline& deadline)
      : S_(S), solver_(solver), deadline_(deadline), x_(S.rows()), y_(S.rows()) {}
  Eigen::Index rows() const { return S_.rows(); }
  Eigen::Index cols() const { return S_.cols(); }
  void perform_op(const double* x_in, double* y_out) const {
    deadline_.check();
    solver_.solve_upper(x_in, x_.data());
    y_.noalias() = S_ * x_;
    solver_.solve_lower(y_.data(), y_out);
  }
  Eigen::VectorXd eigenvector(const Eigen::VectorXd& x) const {
    Eigen::VectorXd phi(x.size());
    solver_.solve_upper(x.data(), phi.data());
    return phi;
  }

 private:
  const Eigen::SparseMatrix<double>& S_;
  CholeskySolver& solver_;
  const AnalysisDeadline& deadline_;
  mutable Eigen::VectorXd x_, y_;
};

// The largest mu of S phi = mu A phi, A factorized in `solver` (positive
// definite), phi K0-normalized; false when Lanczos did not converge.
// Throws DeadlinePassed.
bool largest_eigenpair(const Eigen::SparseMatrix<double>& S, const Eigen::SparseMatrix<double>& K0,
                       const BucklingOptions& options, CholeskySolver& solver, double& mu,
                       Eigen::VectorXd& phi) {
  StandardForm op(S, solver, options.deadline);
  // 12 Lanczos vectors: the wanted eigenvalue lies apart from the rest (see
  // smallest_load_factor); manta_ray's 8k unknowns converge in one pass of
  // 13 operations, against 21 with 20 vectors and two passes with 8.
  const int ncv = std::min(static_cast<int>(S.rows()), 12);
  Spectra::SymEigsSolver<StandardForm> eigs(op, 1, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, options.max_restarts, options.tolerance);
  if (eigs.info() != Spectra::CompInfo::Successful) return false;
  mu = eigs.eigenvalues()(0);
  phi = op.eigenvector(eigs.eigenvectors().col(0));
  phi /= std::sqrt(phi.dot(K0 * phi));
  return true;
}

// The smallest load factor lambda > 1 of K0 phi = lambda (K0 - KL) phi:
// the largest mu = lambda / (lambda - 1) of K0 phi = mu K_L phi (K_L
// factorized: the loads as they are). Its spectrum sets the wanted one
// apart: the loads' unaffected modes gather at 1, stiffened ones below,
// and the wanted one above, apart from the rest by 1 / (lambda - 1); in
// the form below (K_0 factorized) the wanted nu = 1 / lambda sits next to
// the unaffected modes at 0 while the stiffened ones spread far below,
// and Lanczos crept (manta_ray deployed under gravity: 1000 restarts,
// 18 s, not converged). False when K_L is not positive definite or the
// eigensolver failed; lambda 0 when no lambda > 1 exists. Throws
// DeadlinePassed.
bool smallest_load_factor(const Eigen::SparseMatrix<double>& K0,
                          const Eigen::SparseMatrix<double>& KL, const BucklingOptions& options,
                          CholeskySolver& solver, double& lambda, Eigen::VectorXd& phi) {
  options.deadline.check();
  if (solver.factorize(KL) != FactorizationStatus::PositiveDefinite) return false;
  double mu = 0.0;
  if (!largest_eigenpair(K0, K0, options, solver, mu, phi)) return false;
  lambda = mu > 1.0 ? mu / (mu - 1.0) : 0.0;
  // The loads' unaffected modes (lambda infinite) sit at mu = 1 +
  // round-off: a factor beyond kLargestLoadFactor is one of them, not a
  // buckling load.
  if (!(lambda > 1.0 && lambda < kLargestLoadFactor)) lambda = 0.0;
  return true;
}

// The largest nu of (K0 - KL) phi = nu K0 phi; false when the eigensolver
// failed. Throws DeadlinePassed.
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
  if (solver.factorize(K0) != FactorizationStatus::PositiveDefinite) return false;
  return largest_eigenpair(softening, K0, options, solver, nu, phi);
}

}  // namespace

BucklingResult linearized_buckling(const Eigen::SparseMatrix<double>& K0,
                                   const Eigen::SparseMatrix<double>& KL,
                                   const BucklingOptions& options, CholeskySolver* reused) {
  BucklingResult out;
  const int n = static_cast<int>(K0.rows());
  CholeskySolver own;
  CholeskySolver& solver = reused ? *reused : own;
  const bool definite = n > 0 && (options.unloaded_positive_definite ||
                                  solver.factorize(K0) == FactorizationStatus::PositiveDefinite);
  if (!definite) {
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
      // K_L indefinite, or no convergence: the form on K_0.
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
