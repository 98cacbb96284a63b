// Sparse Cholesky (LL^T) factorization with CHOLMOD for symmetric matrices
// whose sparsity pattern stays fixed over many factorizations (Hessians).
//
// The symbolic analysis (fill-reducing ordering as CHOLMOD chooses it,
// supernodal structure) is computed once per pattern and reused by every
// numeric factorization until a matrix with a different pattern arrives;
// it is shared with the other solvers of the same pattern
// (cholesky_pattern.hpp).
// Only the upper triangle of the (full, both-triangles) input is read. The
// solver keeps its own copy of the matrix, already permuted by the
// fill-reducing ordering, whose pattern always contains the diagonal: a
// diagonal shift needs no new pattern, and CHOLMOD factorizes the copy in
// place.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace xshell {

enum class FactorizationStatus {
  PositiveDefinite,     // LL^T succeeded; solve() may be called
  NotPositiveDefinite,  // a pivot was not positive (indefinite or singular)
  NonFinite,            // the matrix or the shift holds NaN or inf
};

// Counters for benchmarks and tests.
struct CholeskyStats {
  long analyses = 0;               // symbolic analyses
  long reused_patterns = 0;        // of which another solver's, of the same pattern, was reused
  long factorizations = 0;         // numeric factorizations attempted (repeats not counted)
  long failed_factorizations = 0;  // of which not positive definite
  long solves = 0;
};

class CholeskySolver {
 public:
  CholeskySolver();
  ~CholeskySolver();
  CholeskySolver(CholeskySolver&&) noexcept;
  CholeskySolver& operator=(CholeskySolver&&) noexcept;

  // Numeric factorization of A + diag(diagonal_shift). A: n x n, symmetric,
  // compressed; only entries with row <= column are read. diagonal_shift:
  // size n or nullptr for none. Analyzes the pattern first if it is new.
  // The same matrix as the last factorization's (every value equal, the
  // shift included) is not factorized again: its status stands (the
  // eigenmodes' unshifted H and the buckling's K_L, one loaded Hessian).
  FactorizationStatus factorize(const Eigen::SparseMatrix<double>& A,
                                const Eigen::VectorXd* diagonal_shift = nullptr);

  // True after a factorize() that returned PositiveDefinite.
  bool factorized() const;

  // x = (A + diag(shift))^-1 b with the last successful factorization.
  // b, x: size n (may alias). Throws std::logic_error if not factorized().
  void solve(const double* b, double* x);
  Eigen::VectorXd solve(const Eigen::VectorXd& b);

  // The factor's halves. With P (A + shift) P^T = G G^T (P the
  // fill-reducing permutation, G lower triangular): solve_lower gives
  // y = G^-1 P b, solve_upper x = P^T G^-T y, so that
  // solve_upper(solve_lower(b)) = (A + shift)^-1 b. For a symmetric S,
  // G^-1 P S P^T G^-T is symmetric, with the eigenvalues of
  // (A + shift)^-1 S (an eigenvector y of it gives x = P^T G^-T y of the
  // latter): the standard form of a generalized eigenproblem. Same sizes
  // and aliasing as solve(); neither counts in stats().solves.
  void solve_lower(const double* b, double* y);
  void solve_upper(const double* y, double* x);

  Eigen::Index size() const;
  const CholeskyStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace xshell
