// What the solvers see of a model: a smooth total energy (elastic plus the
// potential of dead loads) over a vector of free unknowns q.
//
// The statics solvers look for grad E(q) = 0; the dynamics solvers integrate
// M q'' + C q' + grad E(q) = 0. Both also need the model's chance to
// re-express its unknowns around the current configuration between solver
// iterations (rebase): for the rod linkage this updates the rods' source
// frames and folds each joint's rotation vector into its reference frame.
// A rebase moves nothing, so energy() is unchanged, but it changes what the
// unknowns mean, hence the function being solved.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace xshell {

class Objective {
 public:
  virtual ~Objective() = default;

  // Number of free unknowns.
  virtual Eigen::Index size() const = 0;
  // Current free unknowns.
  virtual Eigen::VectorXd get() const = 0;
  // Moves the model to q (size()). Throws std::domain_error when q is not a
  // valid configuration (for example a degenerate joint).
  virtual void set(const Eigen::VectorXd& q) = 0;

  // Total energy at the current configuration.
  virtual double energy() const = 0;
  // set(q), then energy(); an objective may do both in one pass.
  virtual double set_and_energy(const Eigen::VectorXd& q) {
    set(q);
    return energy();
  }
  // dE/dq at the current configuration (size()).
  virtual Eigen::VectorXd gradient() const = 0;
  // d2E/dq2 at the current configuration: symmetric, both triangles stored,
  // compressed columns. Its sparsity pattern never changes over the life of
  // the objective, so symbolic factorizations can be reused.
  virtual const Eigen::SparseMatrix<double>& hessian() = 0;

  // Per-unknown weights w such that the solve has converged when
  // max_i |w_i g_i| <= gradient_tolerance (dimensionless).
  virtual Eigen::VectorXd gradient_weights() const = 0;

  // Lumped (diagonal) mass of every unknown, positive; for dynamics.
  virtual Eigen::VectorXd mass() const = 0;

  // Re-expresses the unknowns around the current configuration without
  // moving it. When velocity is given (size()), it is transformed so that
  // the motion it describes is unchanged.
  virtual void rebase(Eigen::VectorXd* velocity = nullptr) { (void)velocity; }

  // Optionally, a curve that line searches follow instead of the line
  // q0 + alpha p: it starts at the current configuration q0 with tangent p
  // (the rod linkage turns its edges, docs/model.md section 9.8).
  // begin_path(p) at q0 returns whether there is one; path_point(alpha)
  // then gives its unknowns at alpha, and may move the model (throwing
  // std::domain_error like set()). newton_step: p solves the Newton system
  // of the unshifted Hessian (the curve may then follow it further).
  virtual bool begin_path(const Eigen::VectorXd& p, bool newton_step) {
    (void)p;
    (void)newton_step;
    return false;
  }
  virtual Eigen::VectorXd path_point(double alpha);

  // Optionally, Newton's mixed Hessian (docs/model.md section 9.8): from
  // use_mixed_hessian(p) at q0 on, hessian() takes the internal forces
  // linearized along the step p from q0 wherever it is evaluated, until
  // use_exact_hessian(). Energy and gradient stay exact. By default the
  // Hessian stays exact.
  virtual void use_mixed_hessian(const Eigen::VectorXd& p) { (void)p; }
  virtual void use_exact_hessian() {}
};

// Scope guard of a solve: however it ends (an exception included), the
// objective's Hessian is the exact one again.
class ExactHessianAtExit {
 public:
  explicit ExactHessianAtExit(Objective& objective) : objective_(objective) {}
  ~ExactHessianAtExit() { objective_.use_exact_hessian(); }
  ExactHessianAtExit(const ExactHessianAtExit&) = delete;
  ExactHessianAtExit& operator=(const ExactHessianAtExit&) = delete;

 private:
  Objective& objective_;
};

}  // namespace xshell

namespace xshell {

// The dimensionless convergence measure max_i |w_i g_i| at the objective's
// current configuration (0 when there are no free unknowns).
double gradient_measure(const Objective& objective);

}  // namespace xshell
