// The lowest eigenpairs of a (free) Hessian, mass-weighted:
//   H phi = lambda M phi,  M = diag(mass) > 0,
// so that lambda = omega^2 are squared natural angular frequencies (1/time^2)
// of small vibrations about the state (with the lumped masses of the model;
// at density 1 when the material has none) and the modes are M-orthonormal
// (phi^T M phi = 1). Weighting by M makes the eigenvalues independent of
// how the unknowns mix lengths and angles; a plain H phi = lambda phi would
// not be. lambda_min > 0 iff the state is a strict minimum; a negative one
// means unstable, a zero one a mechanism.
//
// Method: Lanczos with shift-invert (Spectra's SymEigsShiftSolver) on
// A = M^-1/2 H M^-1/2, whose shifted inverse M^1/2 (H - sigma M)^-1 M^1/2 is
// applied with a CHOLMOD LL^T factorization (cholesky_solver.hpp). The
// shift sigma must lie below the lowest eigenvalue, so that H - sigma M is
// positive definite and the eigenvalues nearest sigma are the lowest: it
// is 0 when H itself factorizes, else -tau |H|_F / |m|_2 with tau = 1e-8,
// 4e-8, ... until the factorization succeeds (an indefinite H always gets
// one). Small problems (n <= 4 count + 20) are solved densely (Eigen).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

#include "integrators/stability/analysis_deadline.hpp"

namespace xshell {

struct EigenModesOptions {
  int count = 6;              // eigenpairs wanted (fewer when n is smaller)
  double tolerance = 1e-10;   // Spectra's relative tolerance on the Ritz values
  int max_restarts = 1000;    // Lanczos restarts
  AnalysisDeadline deadline;  // past it: not converged, reason "time_limit"
};

struct EigenModes {
  bool converged = false;
  std::string reason;       // why not, when not ("time_limit": options.deadline passed)
  Eigen::VectorXd values;   // ascending, size k
  Eigen::MatrixXd vectors;  // n x k, M-orthonormal columns
  double shift = 0.0;       // sigma used
};

class CholeskySolver;

// H: n x n symmetric (both triangles stored); mass: n, positive. solver:
// the CHOLMOD solver to factorize H - sigma M with (its symbolic analysis of
// H's pattern is reused, its factorization overwritten), or nullptr for a
// solver of its own.
EigenModes lowest_eigenmodes(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                             const EigenModesOptions& options = {},
                             CholeskySolver* solver = nullptr);

}  // namespace xshell
