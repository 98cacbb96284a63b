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
  // The smallest relative shift that a warm start (ShiftMemory) may begin
  // at. Below initial_tau: just past a bifurcation the lowest eigenvalue is
  // tiny (scary_face's deployment: -1.7e-10 |H| / |M| M), and a shift of
  // 1e-8 makes each step along its mode 1% of the distance already
  // travelled, so the descent from the saddle crept for hundreds of
  // iterations; the memory walks the shift down to just above it instead.
  // Not 0: a singular H (a mechanism) would be shifted towards round-off.
  double smallest_tau = 1e-12;
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
// first_tau > 0 starts the shifted attempts there instead, at smallest_tau
// at the least (a warm start from the shift a nearby Hessian needed:
// ShiftMemory).
ShiftedFactorization factorize_with_shift(CholeskySolver& solver,
                                          const Eigen::SparseMatrix<double>& H,
                                          const Eigen::VectorXd& mass,
                                          const ShiftOptions& options = {}, double first_tau = 0.0);

// The shift of the last shifted factorization in a sequence of nearby
// Hessians (Newton's iterates, a continuation's steps), to start the next
// search one growth factor below it rather than at initial_tau: where the
// Hessians stay indefinite, each iteration then tries two or three shifts
// instead of climbing the whole ladder again (Nocedal and Wright, Numerical
// Optimization, 2006, algorithm 3.3), and the start walks down, one growth
// factor per success, to just above the shift the Hessians need, below
// initial_tau if they need less (ShiftOptions::smallest_tau). Each
// unshifted success of the matrix it remembers lowers the start by one
// growth factor, so the memory fades where that matrix is definite, and is
// forgotten once its start would be below initial_tau.
class ShiftMemory {
 public:
  explicit ShiftMemory(const ShiftOptions& options) : options_(options) {}
  double first_tau() const { return tau_ / options_.growth; }
  void record(const ShiftedFactorization& f) {
    if (f.status != FactorizationStatus::PositiveDefinite) return;
    if (f.shifted) {
      tau_ = f.tau;
      return;
    }
    tau_ /= options_.growth;
    if (first_tau() < options_.initial_tau) tau_ = 0.0;
  }

 private:
  const ShiftOptions& options_;
  double tau_ = 0.0;
};

// True iff LL^T of H itself succeeds: the equilibrium is a strict local
// minimum (up to round-off). Never true for a saddle.
bool is_positive_definite(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H);

}  // namespace xshell
