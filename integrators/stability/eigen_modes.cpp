#include "integrators/stability/eigen_modes.hpp"

#include <Spectra/SymEigsShiftSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

namespace {

// y = M^1/2 (H - sigma M)^-1 M^1/2 x: Spectra's shift-solve operation on
// A = M^-1/2 H M^-1/2.
class MassWeightedShiftSolve {
 public:
  using Scalar = double;
  MassWeightedShiftSolve(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                         CholeskySolver& solver, const AnalysisDeadline& deadline)
      : H_(H), mass_(mass), root_(mass.cwiseSqrt()), solver_(solver), deadline_(deadline) {}
  Eigen::Index rows() const { return H_.rows(); }
  Eigen::Index cols() const { return H_.cols(); }
  // The factorization of H - sigma M is made before (find_shift) for the
  // sigma Spectra passes back here.
  void set_shift(double sigma) {
    if (sigma != factorized_shift_) factorize(sigma);
  }
  bool factorize(double sigma) {
    deadline_.check();
    const Eigen::VectorXd shift = -sigma * mass_;
    factorized_shift_ = sigma;
    return solver_.factorize(H_, &shift) == FactorizationStatus::PositiveDefinite;
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    deadline_.check();
    const Eigen::VectorXd b = root_.cwiseProduct(x);
    y = root_.cwiseProduct(solver_.solve(b));
  }

 private:
  const Eigen::SparseMatrix<double>& H_;
  const Eigen::VectorXd& mass_;
  Eigen::VectorXd root_;
  CholeskySolver& solver_;
  const AnalysisDeadline& deadline_;
  double factorized_shift_ = std::nan("");
};

EigenModes dense_modes(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                       int count) {
  const Eigen::VectorXd inv_root = mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = inv_root.asDiagonal() * Eigen::MatrixXd(H) * inv_root.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(0.5 * (A + A.transpose()));
  EigenModes out;
  if (solver.info() != Eigen::Success) {
    out.reason = "dense eigensolver failed";
    return out;
  }
  out.converged = true;
  out.values = solver.eigenvalues().head(count);
  out.vectors = inv_root.asDiagonal() * solver.eigenvectors().leftCols(count);
  return out;
}

// Shift-invert Lanczos (the header's method). Throws DeadlinePassed.
EigenModes lanczos_modes(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                         const EigenModesOptions& options, int count, CholeskySolver& solver) {
  const int n = static_cast<int>(H.rows());
  EigenModes out;
  MassWeightedShiftSolve op(H, mass, solver, options.deadline);
  double sigma = 0.0;
  if (!op.factorize(sigma)) {
    const double scale = H.norm() / mass.norm();
    bool found = false;
    for (double tau = 1e-8; tau < 1e8 && !found; tau *= 4.0) {
      sigma = -tau * scale;
      found = op.factorize(sigma);
    }
    if (!found) {
      out.reason = "no shift below the lowest eigenvalue factorizes (non-finite Hessian?)";
      return out;
    }
  }
  out.shift = sigma;
  const int ncv = std::min(n, std::max(2 * count + 1, 20));
  Spectra::SymEigsShiftSolver<MassWeightedShiftSolve> eigs(op, count, ncv, sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, options.max_restarts, options.tolerance,
               Spectra::SortRule::SmallestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful) {
    out.reason = "the Lanczos iteration did not converge";
    return out;
  }
  out.converged = true;
  out.values = eigs.eigenvalues();
  out.vectors = mass.cwiseSqrt().cwiseInverse().asDiagonal() * eigs.eigenvectors();
  return out;
}

}  // namespace

EigenModes lowest_eigenmodes(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                             const EigenModesOptions& options, CholeskySolver* reused) {
  const int n = static_cast<int>(H.rows());
  const int count = std::min(options.count, n);
  if (count <= 0) {
    EigenModes out;
    out.converged = true;
    return out;
  }
  if (n <= 4 * count + 20) return dense_modes(H, mass, count);
  CholeskySolver own;
  try {
    return lanczos_modes(H, mass, options, count, reused ? *reused : own);
  } catch (const DeadlinePassed&) {
    EigenModes out;
    out.reason = kTimeLimit;
    return out;
  }
}

}  // namespace xshell
