// What IDA sees of statics by damped dynamics.
//
// Damping C = a M + b S: M the lumped (diagonal) mass, S a symmetric
// positive semidefinite "stiffness" matrix with the Hessian's sparsity
// pattern (or none: b = 0, mass-proportional damping); see
// mass_and_damping.hpp for the choice of a, b and S.
//
// Second-order form, 2n unknowns y = [q; v]:
//   r1 = q' - v
//   r2 = M v' + C v + grad E(q)
// First-order (overdamped) form, n unknowns y = q:
//   r  = C q' + grad E(q)
//
// IDA's Newton matrix is dr/dy + c_j dr/dy'. Second order:
//   J = [ c_j I    -I       ]
//       [ H        c_j M + C ]
// Solving J [dq; dv] = [b1; b2]: row 1 gives dv = c_j dq - b1; substituted
// in row 2, H dq + (c_j M + C)(c_j dq - b1) = b2, so
//   K dq = b2 + (c_j M + C) b1,   K = H + (c_j^2 + a c_j) M + b c_j S,
// then dv = c_j dq - b1. First order: K = H + c_j C = H + a c_j M + b c_j S.
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
#include <Eigen/SparseCore>
#include <functional>
#include <utility>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/linear_algebra/sundials_linear_solver.hpp"

namespace xshell {

enum class DynamicsForm { SecondOrder, FirstOrder };

// C = mass_coefficient M + stiffness_coefficient S.
struct Damping {
  double mass_coefficient = 1.0;       // a >= 0, 1 / time
  double stiffness_coefficient = 0.0;  // b >= 0, time
  // S: n x n, symmetric, both triangles, with the pattern of the
  // objective's Hessian (or a subset of it); ignored when b = 0. C must be
  // positive semidefinite (positive definite for the first-order form).
  Eigen::SparseMatrix<double> stiffness;
  // Decay rate of the slowest motion, for the tolerances on velocities.
  double rate = 1.0;  // 1 / time
};

class DynamicsSystem final : public DirectSolveBackend {
 public:
  // mass: lumped, size n, positive.
  DynamicsSystem(ObjectiveEvaluator& evaluator, DynamicsForm form, Eigen::VectorXd mass,
                 Damping damping);

  Eigen::Index unknowns() const { return mass_.size(); }
  // IDA's system size: 2n (second order) or n.
  Eigen::Index size() const {
    return form_ == DynamicsForm::SecondOrder ? 2 * unknowns() : unknowns();
  }
  DynamicsForm form() const { return form_; }
  const Eigen::VectorXd& mass() const { return mass_; }
  // The damping in force once any blend has ended.
  const Damping& damping() const { return blending_ ? to_ : from_; }

  // Replaces the damping at once (the integrator must be restarted: the
  // derivatives jump).
  void set_damping(Damping damping);
  // Moves C smoothly from its current value (at time start) to `target`
  // over [start, start + duration]: C(t) = (1 - w) C_from + w C_to with w
  // the smoothstep of the elapsed fraction, so that the dynamics change
  // without a jump and the integrator needs no restart. Both ends being
  // positive (semi)definite, so is every C(t).
  void blend_damping(Damping target, double start, double duration);
  // Ends a blend whose interval is over at time t; true while one is running.
  bool update_blend(double t);

  // C(t) x (size n).
  Eigen::VectorXd damping_force(const Eigen::VectorXd& x, double t) const;

  // IDA callbacks; user_data is the DynamicsSystem.
  static int residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* user_data);
  // Stores t and c_j and moves the objective to q (J is the placeholder matrix).
  static int jacobian(realtype t, realtype c_j, N_Vector y, N_Vector yp, N_Vector r, SUNMatrix J,
                      void* user_data, N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);

  int setup() override;
  int solve(const double* b, double* x) override;

  // Derivatives consistent with y at time t at the objective's current
  // configuration (y's q part must be where the objective is): q' = v and
  // v' = -M^-1 (C v + grad E) (second order), or q' = -C^-1 grad E (first
  // order; factorizes C when S is used). Throws std::runtime_error if C
  // cannot be factorized.
  Eigen::VectorXd consistent_derivatives(const Eigen::VectorXd& y, double t);
  // v = -(C(t) + inertia M)^-1 grad E at the objective's current
  // configuration (size n; factorizes C + inertia M when S is used).
  // inertia = 0: the velocity of the overdamped flow; started from it, the
  // second-order form has v' = 0, on its slow manifold, without the fast
  // layer that takes it from rest to the overdamped motion. inertia = 1/T
  // > 0 limits the velocity of weakly damped modes (c << m/T) to about the
  // -T M^-1 grad E they reach from rest in a time T. Throws
  // std::runtime_error if the matrix cannot be factorized.
  Eigen::VectorXd overdamped_velocity(double t, double inertia = 0.0);

  CholeskySolver& cholesky() { return cholesky_; }
  bool last_setup_failed() const { return setup_failed_; }
  // Called from setup() with the c_j of a K that was not positive definite
  // (before IDA picks its next step, so that a step cap set there applies
  // to it). Must not throw.
  void on_indefinite(std::function<void(double cj)> handler) {
    on_indefinite_ = std::move(handler);
  }

 private:
  double weight(double t) const;  // w of the blend at t (0 without one)
  // a(t) and the stiffness part of C(t) added to `out` scaled by s.
  double mass_coefficient(double t) const;
  void add_stiffness(double t, double s, Eigen::SparseMatrix<double>& out) const;

  ObjectiveEvaluator& evaluator_;
  DynamicsForm form_;
  Eigen::VectorXd mass_;
  Damping from_, to_;
  bool blending_ = false;
  double blend_start_ = 0.0, blend_end_ = 0.0;
  double cj_ = 0.0, jacobian_t_ = 0.0;     // of the last Jacobian call
  double setup_cj_ = 0.0, setup_t_ = 0.0;  // of the factorization in cholesky_
  Eigen::SparseMatrix<double> work_;       // H + c_j (stiffness part of C)
  CholeskySolver cholesky_;
  bool setup_failed_ = false;
  std::function<void(double)> on_indefinite_;
};

}  // namespace xshell
