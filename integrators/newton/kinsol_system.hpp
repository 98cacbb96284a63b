// What KINSOL sees of a Newton statics solve: the residual F(q) = grad E(q)
// and its Jacobian, the Hessian, factorized by CHOLMOD.
//
// KINSOL solves J p = -F, i.e. H p = -g, the Newton step. The linear solver
// (a DirectSolveBackend plugged into KINSOL through make_direct_linear_solver)
// asks the objective for its Hessian at the current iterate and factorizes
// it, shifting it by a multiple of the mass matrix when it is indefinite
// (see shifted_factorization.hpp). A shifted step is no longer the Newton
// step of F and KINSOL's merit line search, which assumes J p = -F, usually
// rejects it (descent_step.hpp). A deferred setup (always with
// LineSearch::Energy, for shifted Hessians with KinsolWithEnergyFallback)
// keeps its factorization but declines, so that KINSol returns
// KIN_LSETUP_FAIL at once and the driver takes the step itself, globalized
// on the energy.
#pragma once

#include <Eigen/Core>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"
#include "integrators/linear_algebra/sundials_linear_solver.hpp"

namespace xshell {

class NewtonSystem final : public DirectSolveBackend {
 public:
  NewtonSystem(ObjectiveEvaluator& evaluator, const ShiftOptions& shift);

  // The lumped mass defining the shift direction (size n, positive).
  void set_mass(Eigen::VectorXd mass) { mass_ = std::move(mass); }
  // Which setups decline so that the driver steps itself.
  enum class Deferral { Never, ShiftedSteps, Always };
  void set_deferral(Deferral deferral) { deferral_ = deferral; }

  // KINSOL callbacks; user_data is the NewtonSystem.
  static int residual(N_Vector u, N_Vector f, void* user_data);
  // Jacobian "evaluation": only moves the objective to u, so that setup()
  // factorizes the Hessian there. J is the placeholder matrix.
  static int jacobian(N_Vector u, N_Vector fu, SUNMatrix J, void* user_data, N_Vector tmp1,
                      N_Vector tmp2);

  // Asks the objective for its Hessian at the current iterate ahead of the
  // next setup() or the stability check: an objective that caches it (the
  // linkage's) computes its gradient in the same pass, so the driver's
  // convergence test that follows costs nothing. Timed as setup's Hessian;
  // a failure is left for setup() to report.
  void prepare_hessian();
  int setup() override;
  int solve(const double* b, double* x) override;

  CholeskySolver& cholesky() { return cholesky_; }
  // The last setup's factorization (shift, attempts, status).
  const ShiftedFactorization& last_factorization() const { return last_; }
  // Setups whose factorization failed since the counter was reset, and why.
  bool setup_failed() const { return setup_failed_; }
  // setup() declined (its factorization, possibly shifted, is ready in cholesky()).
  bool deferred() const { return deferred_; }
  void reset_iteration_flags() {
    setup_failed_ = deferred_ = any_shift_ = false;
    max_shift_ = 0.0;
    hessian_seconds_ = factorization_seconds_ = 0.0;
  }
  // Wall time of the setups since reset_iteration_flags(): Hessian
  // assembly, and the numeric factorizations (shifted retries included).
  double hessian_seconds() const { return hessian_seconds_; }
  double factorization_seconds() const { return factorization_seconds_; }
  bool any_shift() const { return any_shift_; }
  double max_shift() const { return max_shift_; }

 private:
  ObjectiveEvaluator& evaluator_;
  ShiftOptions shift_options_;
  Eigen::VectorXd mass_;
  CholeskySolver cholesky_;
  ShiftedFactorization last_;
  Deferral deferral_ = Deferral::Never;
  bool setup_failed_ = false;
  bool deferred_ = false;
  bool any_shift_ = false;
  double max_shift_ = 0.0;
  double hessian_seconds_ = 0.0;
  double factorization_seconds_ = 0.0;
};

}  // namespace xshell
