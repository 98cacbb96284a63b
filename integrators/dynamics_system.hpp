// What IDA sees of statics by damped dynamics.
//
// Second-order form, 2n unknowns y = [q; v]:
//   r1 = q' - v
//   r2 = M v' + C v + grad E(q),          C = c M (M lumped, diagonal)
// First-order (overdamped) form, n unknowns y = q:
//   r  = C q' + grad E(q)
//
// IDA's Newton matrix is dr/dy + c_j dr/dy'. Second order:
//   J = [ c_j I    -I       ]
//       [ H        c_j M + C ]
// Solving J [dq; dv] = [b1; b2]: row 1 gives dv = c_j dq - b1; substituted
// in row 2, H dq + (c_j M + C)(c_j dq - b1) = b2, so
//   K dq = b2 + (c_j M + C) b1,   K = H + (c_j^2 + c c_j) M,
// then dv = c_j dq - b1. First order: K = H + c c_j M directly.
//
// Why a Schur complement and Cholesky rather than KLU on the 2n system: K
// is symmetric with the pattern of H (plus its diagonal), so the Newton
// solver's CHOLMOD analysis and code are reused, the factorization is of
// size n instead of a non-symmetric LU of size 2n, and no 2n pattern has to
// be assembled. K fails to be positive definite only when H is indefinite
// and the step is long (c_j small) compared with the instability's time
// scale: setup() then reports a recoverable failure and IDA retries with a
// shorter step, which is the physically right reaction near a saddle.
#pragma once

#include <Eigen/Core>

#include "cholesky_solver.hpp"
#include "direct_linear_solver.hpp"
#include "objective_evaluator.hpp"

namespace xshell {

enum class DynamicsForm { SecondOrder, FirstOrder };

class DynamicsSystem final : public DirectSolveBackend {
 public:
  // mass: lumped, size n, positive; damping: c > 0.
  DynamicsSystem(ObjectiveEvaluator& evaluator, DynamicsForm form, Eigen::VectorXd mass,
                 double damping);

  Eigen::Index unknowns() const { return mass_.size(); }
  // IDA's system size: 2n (second order) or n.
  Eigen::Index size() const {
    return form_ == DynamicsForm::SecondOrder ? 2 * unknowns() : unknowns();
  }
  DynamicsForm form() const { return form_; }
  const Eigen::VectorXd& mass() const { return mass_; }
  double damping() const { return damping_; }

  // IDA callbacks; user_data is the DynamicsSystem.
  static int residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* user_data);
  // Stores c_j and moves the objective to q (J is the placeholder matrix).
  static int jacobian(realtype t, realtype c_j, N_Vector y, N_Vector yp, N_Vector r, SUNMatrix J,
                      void* user_data, N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);

  int setup() override;
  int solve(const double* b, double* x) override;

  // Derivatives consistent with y at the objective's current configuration
  // (y's q part must be where the objective is): q' = v and
  // v' = -c v - M^-1 grad E (second order), or q' = -(c M)^-1 grad E.
  Eigen::VectorXd consistent_derivatives(const Eigen::VectorXd& y);

  CholeskySolver& cholesky() { return cholesky_; }
  bool last_setup_failed() const { return setup_failed_; }

 private:
  ObjectiveEvaluator& evaluator_;
  DynamicsForm form_;
  Eigen::VectorXd mass_;
  double damping_;
  double cj_ = 0.0;        // c_j of the last Jacobian call
  double setup_cj_ = 0.0;  // c_j of the factorization in cholesky_
  CholeskySolver cholesky_;
  bool setup_failed_ = false;
};

}  // namespace xshell
