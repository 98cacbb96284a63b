#include "integrators/newton/newton.hpp"

#include <kinsol/kinsol.h>
#include <kinsol/kinsol_ls.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/linear_algebra/sundials_handles.hpp"
#include "integrators/newton/descent_step.hpp"
#include "integrators/newton/kinsol_system.hpp"

namespace xshell {

const char* to_string(NewtonStatus status) {
  switch (status) {
    case NewtonStatus::Converged:
      return "converged";
    case NewtonStatus::MaxIterations:
      return "maximum number of iterations reached";
    case NewtonStatus::LinearSolverFailed:
      return "linear solver failed";
    case NewtonStatus::LineSearchFailed:
      return "line search failed";
    case NewtonStatus::NonFinite:
      return "non-finite values";
    case NewtonStatus::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

namespace {

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

// Smallest function scale passed to KINSOL, which requires positive scales;
// an unknown of weight 0 is then (practically) ignored, as in our measure.
constexpr double kMinimumScale = 1e-300;

}  // namespace

struct NewtonSolver::Impl {
  // Declaration order = construction order; SUNDIALS objects after the context.
  SunContext context;
  ObjectiveEvaluator evaluator;
  NewtonSystem system;
  NVector u, u_scale, f_scale;
  SunMatrix placeholder;
  SunLinearSolver linear_solver;
  KinsolMemory kinsol;
  std::string last_message;

  Impl(Objective& objective, const NewtonOptions& options)
      : evaluator(objective), system(evaluator, options.shift) {
    const Eigen::Index n = objective.size();
    u = make_serial_vector(n, context);
    u_scale = make_serial_vector(n, context);
    f_scale = make_serial_vector(n, context);
    N_VConst(1.0, u_scale.get());
    N_VConst(1.0, f_scale.get());
    placeholder = make_placeholder_matrix(context);
    linear_solver = make_direct_linear_solver(context, system);
    kinsol.reset(KINCreate(context));
    if (!kinsol) throw std::bad_alloc();
    void* k = kinsol.get();
    check_sundials(KINInit(k, &NewtonSystem::residual, u.get()), "KINInit");
    check_sundials(KINSetUserData(k, &system), "KINSetUserData");
    check_sundials(KINSetErrHandlerFn(k, keep_sundials_message, &last_message),
                   "KINSetErrHandlerFn");
    check_sundials(KINSetLinearSolver(k, linear_solver.get(), placeholder.get()),
                   "KINSetLinearSolver");
    check_sundials(KINSetJacFn(k, &NewtonSystem::jacobian), "KINSetJacFn");
    check_sundials(KINSetNumMaxIters(k, 1), "KINSetNumMaxIters");
    check_sundials(KINSetMaxSetupCalls(k, 1), "KINSetMaxSetupCalls");
    check_sundials(KINSetNoResMon(k, SUNTRUE), "KINSetNoResMon");
    check_sundials(KINSetFuncNormTol(k, options.gradient_tolerance), "KINSetFuncNormTol");
    check_sundials(KINSetScaledStepTol(k, options.scaled_step_tolerance), "KINSetScaledStepTol");
    check_sundials(KINSetMaxNewtonStep(k, options.max_step), "KINSetMaxNewtonStep");
  }
};

NewtonSolver::NewtonSolver(Objective& objective, NewtonOptions options)
    : objective_(objective), options_(options) {
  if (objective.size() > 0) impl_ = std::make_unique<Impl>(objective, options_);
}

NewtonSolver::~NewtonSolver() = default;

CholeskyStats NewtonSolver::cholesky_stats() const {
  return impl_ ? impl_->system.cholesky().stats() : CholeskyStats{};
}

namespace {

// Maps a failed KINSol flag (not SUCCESS / MAXITER_REACHED) to a result.
void classify_failure(int flag, const ObjectiveEvaluator& evaluator, const NewtonSystem& system,
                      const std::string& message, NewtonResult& result) {
  const bool nonfinite = evaluator.last_failure() == EvaluationFailure::NonFinite;
  const std::string detail = evaluator.last_message().empty() ? message : evaluator.last_message();
  switch (flag) {
    case KIN_LSETUP_FAIL:
    case KIN_LSOLVE_FAIL:
    case KIN_LINSOLV_NO_RECOVERY:
      if (nonfinite) {
        result.status = NewtonStatus::NonFinite;
        result.reason = "linear solver setup: " + detail;
      } else {
        result.status = NewtonStatus::LinearSolverFailed;
        result.reason = system.setup_failed()
                            ? "the Hessian could not be factorized even with the largest shift"
                            : "linear solver failed: " + message;
      }
      return;
    case KIN_SYSFUNC_FAIL:
    case KIN_FIRST_SYSFUNC_ERR:
    case KIN_REPTD_SYSFUNC_ERR:
      result.status = nonfinite ? NewtonStatus::NonFinite : NewtonStatus::LineSearchFailed;
      result.reason = "the objective failed at every trial point: " + detail;
      return;
    case KIN_LINESEARCH_NONCONV:
    case KIN_LINESEARCH_BCFAIL:
    case KIN_STEP_LT_STPTOL:
    case KIN_MXNEWT_5X_EXCEEDED:
      result.status = NewtonStatus::LineSearchFailed;
      result.reason = "KINSOL: " + kinsol_flag_name(flag) +
                      (system.any_shift() ? " after a shifted (indefinite Hessian) step" : "");
      return;
    default:
      throw std::runtime_error("KINSol failed: " + kinsol_flag_name(flag) + ": " + message);
  }
}

}  // namespace

NewtonResult NewtonSolver::solve(const NewtonCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  NewtonResult result;
  if (!impl_) {  // no unknowns: trivially in equilibrium
    result.status = NewtonStatus::Converged;
    result.reason = "no free unknowns";
    result.energy = objective_.energy();
    result.stable = true;
    return result;
  }
  Impl& s = *impl_;
  const long factorizations_before = s.system.cholesky().stats().factorizations;
  auto total_factorizations = [&] {
    return s.system.cholesky().stats().factorizations - factorizations_before;
  };
  // Every iteration starts right after a rebase: here, and after each step
  // (so that the gradient of the rebased state serves both the convergence
  // test and the next iteration).
  objective_.rebase();
  s.evaluator.sync();
  s.evaluator.clear_failures();
  s.system.prepare_hessian();
  s.system.set_mass(objective_.mass());
  s.system.set_deferral(options_.line_search == LineSearch::Kinsol ? NewtonSystem::Deferral::Never
                        : options_.line_search == LineSearch::Energy
                            ? NewtonSystem::Deferral::Always
                            : NewtonSystem::Deferral::ShiftedSteps);
  bool stagnant = false;  // the last step was below the scaled step tolerance
  DescentStepOptions descent;
  descent.max_step = options_.max_step;

  NewtonReport report;
  report.energy = objective_.energy();
  report.gradient_measure =
      weighted_max_norm(objective_.gradient_weights(), s.evaluator.gradient());
  if (callbacks.on_iteration) callbacks.on_iteration(report);

  for (int iteration = 0;; ++iteration) {
    result.iterations = iteration;
    result.energy = report.energy;
    result.gradient_measure = report.gradient_measure;
    if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure)) {
      result.status = NewtonStatus::NonFinite;
      result.reason =
          "energy or gradient not finite after " + std::to_string(iteration) + " iterations";
      break;
    }
    if (report.gradient_measure <= options_.gradient_tolerance) {
      result.status = NewtonStatus::Converged;
      result.reason = "gradient measure " + scientific(report.gradient_measure) + " <= tolerance";
      break;
    }
    if (stagnant) {
      result.status = NewtonStatus::LineSearchFailed;
      result.reason =
          "stagnation: the step fell below the scaled step tolerance at gradient measure " +
          scientific(report.gradient_measure) + " (round-off floor above the tolerance?)";
      break;
    }
    if (callbacks.stop != nullptr && callbacks.stop->load()) {
      result.status = NewtonStatus::Interrupted;
      result.reason = "stop flag raised";
      break;
    }
    if (iteration >= options_.max_iterations) {
      result.status = NewtonStatus::MaxIterations;
      result.reason = "no convergence in " + std::to_string(iteration) + " iterations";
      break;
    }

    const Clock::time_point iteration_start = Clock::now();
    const long factorizations_at_start = total_factorizations();
    const Eigen::VectorXd q0 = s.evaluator.position();
    const Eigen::VectorXd weights = objective_.gradient_weights();
    as_eigen(s.f_scale.get()) = weights.cwiseAbs().cwiseMax(kMinimumScale);
    as_eigen(s.u.get()) = q0;
    s.system.reset_iteration_flags();
    s.evaluator.clear_failures();

    // An unexpected exception in a callback: back to q0 (best effort), then rethrow.
    auto rethrow_if_fatal = [&] {
      if (!s.evaluator.has_fatal()) return;
      try {
        objective_.set(q0);
      } catch (...) {
      }
      s.evaluator.rethrow_if_fatal();
    };
    int flag = KINSol(s.kinsol.get(), s.u.get(), KIN_LINESEARCH, s.u_scale.get(), s.f_scale.get());
    rethrow_if_fatal();
    report.energy_line_search = false;
    double accepted_energy = 0.0;  // known after an energy line search step
    if (flag == KIN_LSETUP_FAIL && s.system.deferred()) {
      // The (possibly shifted) factorization is ready: step on the energy.
      report.energy_line_search = true;
      s.evaluator.move_to(q0);
      const Eigen::VectorXd g0 = s.evaluator.gradient();
      const DescentStepResult step =
          energy_descent_step(s.evaluator, s.system.cholesky(), q0, report.energy, g0, descent);
      rethrow_if_fatal();
      if (!step.accepted) {
        objective_.set(q0);  // the last good state
        s.evaluator.sync();
        const bool all_rejected = step.trials > 0 && step.rejected_configurations == step.trials;
        const EvaluationFailure why = s.evaluator.last_failure();
        result.status = all_rejected && why == EvaluationFailure::NonFinite
                            ? NewtonStatus::NonFinite
                            : NewtonStatus::LineSearchFailed;
        result.reason = all_rejected ? "the objective failed at every trial point: " +
                                           s.evaluator.last_message()
                                     : "no energy decrease along the Newton step";
        break;
      }
      as_eigen(s.u.get()) = s.evaluator.position();
      accepted_energy = step.energy;
      flag = KIN_SUCCESS;
    }
    const bool accepted =
        flag == KIN_SUCCESS || flag == KIN_MAXITER_REACHED || flag == KIN_INITIAL_GUESS_OK;
    if (!accepted) {
      objective_.set(q0);  // the last good state
      s.evaluator.sync();
      classify_failure(flag, s.evaluator, s.system, s.last_message, result);
      break;
    }
    const Eigen::Map<Eigen::VectorXd> q = as_eigen(s.u.get());
    s.evaluator.move_to(q);

    report.iteration = iteration + 1;
    report.energy = report.energy_line_search ? accepted_energy : objective_.energy();
    if (!std::isfinite(report.energy)) {
      // KINSOL's line search watches the gradient only: a step to a point
      // with a finite gradient but no finite energy is not a good state.
      objective_.set(q0);  // the last good state
      s.evaluator.sync();
      report.energy = result.energy;
      result.status = NewtonStatus::NonFinite;
      result.reason = "the energy is not finite after the step of iteration " +
                      std::to_string(iteration + 1) + "; the state before it is kept";
      break;
    }
    report.step_norm = (q - q0).lpNorm<Eigen::Infinity>();
    // KINSOL's own stagnation test (KINScSNorm with unit scaling); KINSOL
    // applies it itself to the steps it takes.
    stagnant = report.energy_line_search &&
               ((q - q0).array().abs() / (1.0 + q.array().abs())).maxCoeff() <=
                   options_.scaled_step_tolerance;
    // The rebase moves nothing (the energy stays), but re-expresses q.
    objective_.rebase();
    s.evaluator.sync();
    s.system.prepare_hessian();
    report.gradient_measure = weighted_max_norm(weights, s.evaluator.gradient());
    report.factorizations = total_factorizations() - factorizations_at_start;
    report.shifted = s.system.any_shift();
    report.shift = s.system.max_shift();
    report.seconds = seconds_since(iteration_start);
    report.hessian_seconds = s.system.hessian_seconds();
    report.factorization_seconds = s.system.factorization_seconds();
    if (callbacks.on_iteration) callbacks.on_iteration(report);
  }

  if (result.status != NewtonStatus::NonFinite) {
    result.stable = is_positive_definite(s.system.cholesky(), objective_.hessian());
  }
  result.factorizations = total_factorizations();
  result.seconds = seconds_since(start);
  return result;
}

NewtonResult solve_newton(Objective& objective, const NewtonOptions& options,
                          const NewtonCallbacks& callbacks) {
  return NewtonSolver(objective, options).solve(callbacks);
}

}  // namespace xshell
