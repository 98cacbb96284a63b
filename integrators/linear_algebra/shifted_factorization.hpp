// Factorization of a possibly indefinite Hessian for Newton-type steps.
//
// Strategy of the reference implementation (ElasticRods' Newton solver):
// try LL^T of H; if it fails, factorize H + tau * (|H| / |M|) * M instead,
// with M the lumped (diagonal) mass matrix and tau = initial_tau, then
// growth * tau, ... until the factorization succeeds. Here |H| is the
// Frobenius norm of the full Hessian and |M| = ||diag(M)||_2 (the Frobenius
// norm of M), so the shift is scale-invariant: multiplying the energy by a
// constant or the masses by a constant does not change tau. The resulting
// step -(H + shift M)^-1 g is a descent direction of the energy; once the
// Hessian is positive definite again, tau is not used and Newton's
// quadratic convergence returns.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

struct ShiftOptions {
  double initial_tau = 1e-8;  // first relative shift tried after LL^T of H fails
  double growth = 4.0;        // tau multiplier between attempts
  int max_attempts = 40;      // shifted attempts before giving up (tau up to ~1e16)
};

struct ShiftedFactorization {
  FactorizationStatus status = FactorizationStatus::NotPositiveDefinite;
  bool shifted = false;    // the unshifted Hessian was not positive definite
  double tau = 0.0;        // relative shift of the successful attempt (0 if unshifted)
  double shift = 0.0;      // absolute coefficient tau * |H| / |M| multiplying M
  int factorizations = 0;  // numeric factorizations attempted
};

// Factorizes H (n x n, both triangles) into `solver`, shifting by multiples
// of diag(mass) (size n, positive) as described above when H is not
// positive definite. status is PositiveDefinite on success (solver ready),
// NonFinite if H holds NaN/inf, NotPositiveDefinite if every attempt failed.
// first_tau > initial_tau starts the shifted attempts there instead (a
// warm start from the shift a nearby Hessian needed: ShiftMemory).
ShiftedFactorization factorize_with_shift(CholeskySolver& solver,
                                          const Eigen::SparseMatrix<double>& H,
                                          const Eigen::VectorXd& mass,
                                          const ShiftOptions& options = {}, double first_tau = 0.0);

// The shift of the last shifted factorization in a sequence of nearby
// Hessians (Newton's iterates, a continuation's steps), to start the next
// search one growth factor below it rather than at initial_tau: where the
// Hessians stay indefinite, each iteration then tries two or three shifts
// instead of climbing the whole ladder again (Nocedal and Wright, Numerical
// Optimization, 2006, algorithm 3.3). Each unshifted success of the matrix
// it remembers lowers the start by one growth factor, so the memory fades
// where that matrix is definite.
class ShiftMemory {
 public:
  explicit ShiftMemory(const ShiftOptions& options) : options_(options) {}
  double first_tau() const { return tau_ / options_.growth; }
  void record(const ShiftedFactorization& f) {
    if (f.status != FactorizationStatus::PositiveDefinite) return;
    tau_ = f.shifted ? f.tau : tau_ / options_.growth;
  }

 private:
  const ShiftOptions& options_;
  double tau_ = 0.0;
};

// True iff LL^T of H itself succeeds: the equilibrium is a strict local
// minimum (up to round-off). Never true for a saddle.
bool is_positive_definite(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H);

}  // namespace xshell
