#include "integrators/dynamics/ida_integrator.hpp"

#include <ida/ida.h>
#include <ida/ida_ls.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>

namespace xshell {

IdaIntegrator::IdaIntegrator(DynamicsSystem& system, const DynamicsOptions& options,
                             const Eigen::VectorXd& y0, const Eigen::VectorXd& yp0,
                             const Eigen::VectorXd& absolute_tolerances) {
  const Eigen::Index size = system.size();
  y = make_serial_vector(size, context);
  yp = make_serial_vector(size, context);
  atol = make_serial_vector(size, context);
  as_eigen(y.get()) = y0;
  as_eigen(yp.get()) = yp0;
  as_eigen(atol.get()) = absolute_tolerances;
  placeholder = make_placeholder_matrix(context);
  linear_solver = make_direct_linear_solver(context, system);
  ida.reset(IDACreate(context));
  if (!ida) throw std::bad_alloc();
  void* m = ida.get();
  check_sundials(IDAInit(m, &DynamicsSystem::residual, 0.0, y.get(), yp.get()), "IDAInit");
  check_sundials(IDASVtolerances(m, options.error_control.relative_tolerance, atol.get()),
                 "IDASVtolerances");
  check_sundials(IDASetUserData(m, &system), "IDASetUserData");
  check_sundials(IDASetErrHandlerFn(m, keep_sundials_message, &last_message), "IDASetErrHandlerFn");
  check_sundials(IDASetMaxNumSteps(m, std::max(options.stopping.max_steps, 500L)),
                 "IDASetMaxNumSteps");
  check_sundials(IDASetLinearSolver(m, linear_solver.get(), placeholder.get()),
                 "IDASetLinearSolver");
  check_sundials(IDASetJacFn(m, &DynamicsSystem::jacobian), "IDASetJacFn");
  if (options.start.initial_step > 0.0)
    check_sundials(IDASetInitStep(m, options.start.initial_step), "IDASetInitStep");
  // The gradient flow at BDF orders 3-5 (not A-stable) let the energy rise
  // by 1e-6 of its drop while a column buckled; orders 1-2 do not.
  const int order = system.form() == DynamicsForm::FirstOrder ? std::min(2, options.steps.max_order)
                                                              : options.steps.max_order;
  check_sundials(IDASetMaxOrd(m, order), "IDASetMaxOrd");
  if (options.error_control.suppress_velocity && size > system.unknowns()) {
    id = make_serial_vector(size, context);
    Eigen::Map<Eigen::VectorXd> ids = as_eigen(id.get());
    ids.head(system.unknowns()).setOnes();
    ids.tail(size - system.unknowns()).setZero();
    check_sundials(IDASetId(m, id.get()), "IDASetId");
    check_sundials(IDASetSuppressAlg(m, SUNTRUE), "IDASetSuppressAlg");
  }
  check_sundials(IDASetEtaMax(m, options.steps.eta_max), "IDASetEtaMax");
}

void classify_failure(int flag, const ObjectiveEvaluator& evaluator, const DynamicsSystem& system,
                      const std::string& message, DynamicsResult& result) {
  const bool nonfinite = evaluator.last_failure() == EvaluationFailure::NonFinite;
  const bool invalid = evaluator.last_failure() == EvaluationFailure::InvalidConfiguration;
  const std::string name = ida_flag_name(flag);
  switch (flag) {
    case IDA_MEM_NULL:
    case IDA_ILL_INPUT:
    case IDA_NO_MALLOC:
    case IDA_MEM_FAIL:
    case IDA_BAD_EWT:
      throw std::runtime_error("IDASolve failed: " + name + ": " + message);
    default:
      break;
  }
  if (nonfinite) {
    result.status = SolveStatus::NonFinite;
    result.reason = name + ": " + evaluator.last_message();
  } else if (flag == IDA_LSETUP_FAIL || system.last_setup_failed()) {
    result.status = SolveStatus::LinearSolverFailed;
    result.reason = name +
                    ": the implicit step's matrix K = H + c_j C + (c_j^2 + a c_j) M (H + c_j C " +
                    "in first order) was not positive definite even for short steps";
  } else if (flag == IDA_LSOLVE_FAIL) {
    result.status = SolveStatus::LinearSolverFailed;
    result.reason = name +
                    ": the linear solve with K gave no finite correction even for short steps " +
                    "(K numerically singular)";
  } else {
    result.status = SolveStatus::IntegratorFailed;
    result.reason = name + (invalid ? ": " + evaluator.last_message() : ": " + message);
  }
}

Eigen::VectorXd unknown_scales(const Eigen::VectorXd& weights) {
  const Eigen::VectorXd w = weights.cwiseAbs();
  const double smallest = w.size() > 0 ? w.minCoeff() : 0.0;
  if (!(smallest > 0.0) || !w.allFinite()) return Eigen::VectorXd::Ones(w.size());
  return w / smallest;
}

namespace {

using ConstRef = Eigen::Ref<const Eigen::VectorXd>;

// Root mean square of x / (rtol |y| + atol), IDA's error norm, over the
// first x.size() entries of y and atol.
double weighted_rms(const ConstRef& x, const ConstRef& y, const ConstRef& atol, double rtol) {
  const Eigen::Index m = x.size();
  if (m == 0) return 0.0;
  const Eigen::ArrayXd weight = rtol * y.head(m).array().abs() + atol.head(m).array();
  return std::sqrt((x.array() / weight).square().sum() / static_cast<double>(m));
}

}  // namespace

double first_step(const ConstRef& y, const ConstRef& yp, const ConstRef& atol, double rtol,
                  Eigen::Index n, bool q_only) {
  double h = std::numeric_limits<double>::infinity();
  if (q_only) {
    const double v = weighted_rms(yp.head(n), y, atol, rtol);
    const double a = weighted_rms(yp.tail(n), y, atol, rtol);  // q's weights
    if (v > 0.0) h = 0.5 / v;
    if (a > 0.0) h = std::min(h, 1.0 / std::sqrt(a));
  } else {
    const double norm = weighted_rms(yp, y, atol, rtol);
    if (norm > 0.0) h = 0.5 / norm;
  }
  return std::isfinite(h) ? h : 0.0;
}

}  // namespace xshell
