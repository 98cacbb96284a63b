#include "dynamics.hpp"

#include <ida/ida.h>
#include <ida/ida_ls.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mass_and_damping.hpp"
#include "objective_evaluator.hpp"
#include "sundials_handles.hpp"

namespace xshell {

const char* to_string(DynamicsStatus status) {
  switch (status) {
    case DynamicsStatus::Converged:
      return "converged";
    case DynamicsStatus::MaxSteps:
      return "maximum number of steps reached";
    case DynamicsStatus::LinearSolverFailed:
      return "linear solver failed";
    case DynamicsStatus::IntegratorFailed:
      return "integrator failed";
    case DynamicsStatus::NonFinite:
      return "non-finite values";
    case DynamicsStatus::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

namespace {

using Clock = std::chrono::steady_clock;

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

// A step shorter than this fraction of the simulated time means the
// integrator is creeping towards a barrier (configurations it cannot
// evaluate) and no longer advances time in floating point.
constexpr double kStagnantStepRatio = 1e-12;

// IDA and everything it owns; declaration order = construction order, the
// context first so that it is destroyed last. The DynamicsSystem (the
// linear solver's backend) must outlive this object.
struct IdaIntegrator {
  SunContext context;
  NVector y, yp, atol;
  SunMatrix placeholder;
  SunLinearSolver linear_solver;
  IdaMemory ida;
  std::string last_message;

  IdaIntegrator(DynamicsSystem& system, const DynamicsOptions& options, const Eigen::VectorXd& y0,
                const Eigen::VectorXd& yp0) {
    const Eigen::Index size = system.size(), n = system.unknowns();
    y = make_serial_vector(size, context);
    yp = make_serial_vector(size, context);
    atol = make_serial_vector(size, context);
    as_eigen(y.get()) = y0;
    as_eigen(yp.get()) = yp0;
    Eigen::Map<Eigen::VectorXd> a = as_eigen(atol.get());
    a.head(n).setConstant(options.absolute_tolerance);
    if (size > n) a.tail(size - n).setConstant(options.absolute_tolerance * 0.5 * system.damping());
    placeholder = make_placeholder_matrix(context);
    linear_solver = make_direct_linear_solver(context, system);
    ida.reset(IDACreate(context));
    if (!ida) throw std::bad_alloc();
    void* m = ida.get();
    check_sundials(IDAInit(m, &DynamicsSystem::residual, 0.0, y.get(), yp.get()), "IDAInit");
    check_sundials(IDASVtolerances(m, options.relative_tolerance, atol.get()), "IDASVtolerances");
    check_sundials(IDASetUserData(m, &system), "IDASetUserData");
    check_sundials(IDASetErrHandlerFn(m, keep_sundials_message, &last_message),
                   "IDASetErrHandlerFn");
    check_sundials(IDASetMaxNumSteps(m, std::max(options.max_steps, 500L)), "IDASetMaxNumSteps");
    check_sundials(IDASetLinearSolver(m, linear_solver.get(), placeholder.get()),
                   "IDASetLinearSolver");
    check_sundials(IDASetJacFn(m, &DynamicsSystem::jacobian), "IDASetJacFn");
    if (options.initial_step > 0.0)
      check_sundials(IDASetInitStep(m, options.initial_step), "IDASetInitStep");
  }
};

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
    result.status = DynamicsStatus::NonFinite;
    result.reason = name + ": " + evaluator.last_message();
  } else if (flag == IDA_LSETUP_FAIL || flag == IDA_LSOLVE_FAIL || system.last_setup_failed()) {
    result.status = DynamicsStatus::LinearSolverFailed;
    result.reason = name + ": K = H + (c_j^2 + c c_j) M not positive definite even for short steps";
  } else {
    result.status = DynamicsStatus::IntegratorFailed;
    result.reason = name + (invalid ? ": " + evaluator.last_message() : ": " + message);
  }
}

}  // namespace

DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options,
                              const DynamicsCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  DynamicsResult result;
  const Eigen::Index n = objective.size();
  if (n == 0) {
    result.status = DynamicsStatus::Converged;
    result.reason = "no free unknowns";
    result.energy = objective.energy();
    result.stable = true;
    return result;
  }
  ObjectiveEvaluator evaluator(objective);
  evaluator.sync();

  // Mass and damping from the starting configuration.
  CholeskySolver estimator;
  const Eigen::SparseMatrix<double>& H0 = objective.hessian();
  Eigen::VectorXd mass =
      options.mass == MassModel::Physical ? objective.mass() : fictitious_mass(H0);
  double damping = options.damping;
  if (!(damping > 0.0)) {
    const LowestMode mode =
        estimate_lowest_mode(estimator, H0, mass, options.damping_iterations, options.shift);
    damping = automatic_damping(mode, H0, mass);
  }
  result.damping = damping;
  DynamicsSystem system(evaluator, options.form, mass, damping);
  const bool second_order = options.form == DynamicsForm::SecondOrder;

  // Initial state at rest.
  Eigen::VectorXd y(system.size());
  y.head(n) = objective.get();
  if (second_order) y.tail(n).setZero();
  Eigen::VectorXd weights = objective.gradient_weights();
  const double energy0 = objective.energy();
  DynamicsReport report;
  report.energy = energy0;
  report.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
  if (callbacks.on_step) callbacks.on_step(report);

  auto kinetic = [&](const Eigen::VectorXd& state) {
    return second_order ? 0.5 * state.tail(n).dot(mass.cwiseProduct(state.tail(n))) : 0.0;
  };
  auto finish = [&](DynamicsStatus status, std::string reason) {
    result.status = status;
    result.reason = std::move(reason);
  };

  if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure)) {
    finish(DynamicsStatus::NonFinite, "energy or gradient not finite at the start");
  } else if (report.gradient_measure <= options.gradient_tolerance) {
    finish(DynamicsStatus::Converged, "in equilibrium at the start");
  } else {
    IdaIntegrator integrator(system, options, y, system.consistent_derivatives(y));
    const double time_scale = 2.0 / damping;
    Eigen::VectorXd last_good = y;
    double t = 0.0;
    for (;;) {
      if (callbacks.stop != nullptr && callbacks.stop->load()) {
        finish(DynamicsStatus::Interrupted, "stop flag raised");
        break;
      }
      if (result.steps >= options.max_steps) {
        finish(DynamicsStatus::MaxSteps,
               "no convergence in " + std::to_string(result.steps) + " steps");
        break;
      }
      evaluator.clear_failures();
      const int flag = IDASolve(integrator.ida.get(), t + 1e10 * time_scale, &t, integrator.y.get(),
                                integrator.yp.get(), IDA_ONE_STEP);
      if (evaluator.has_fatal()) {  // an unexpected exception in a callback
        try {
          objective.set(last_good.head(n));
        } catch (...) {
        }
        evaluator.rethrow_if_fatal();
      }
      if (flag < 0) {
        classify_failure(flag, evaluator, system, integrator.last_message, result);
        y = last_good;
        break;
      }
      ++result.steps;
      y = as_eigen(integrator.y.get());
      if (evaluator.move_to(y.data()) != 0) {  // IDA's corrected y was never evaluated
        evaluator.rethrow_if_fatal();
        finish(DynamicsStatus::IntegratorFailed,
               "the objective rejected an accepted step: " + evaluator.last_message());
        y = last_good;
        break;
      }
      double h = 0.0;
      IDAGetLastStep(integrator.ida.get(), &h);
      report.step = result.steps;
      report.time = t;
      report.step_size = h;
      report.energy = objective.energy();
      report.kinetic_energy = kinetic(y);
      report.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
      if (callbacks.on_step) callbacks.on_step(report);
      if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure) ||
          !y.allFinite()) {
        finish(DynamicsStatus::NonFinite,
               "non-finite state after step " + std::to_string(result.steps));
        y = last_good;
        break;
      }
      if (h <= kStagnantStepRatio * t) {
        const bool nonfinite = evaluator.last_failure() == EvaluationFailure::NonFinite;
        finish(nonfinite ? DynamicsStatus::NonFinite : DynamicsStatus::IntegratorFailed,
               "step size " + scientific(h) + " stagnant at t = " + scientific(t) +
                   (evaluator.last_message().empty() ? "" : ": " + evaluator.last_message()));
        break;
      }
      last_good = y;
      const double energy_scale =
          std::max(std::abs(energy0 - report.energy), std::abs(report.energy));
      if (report.gradient_measure <= options.gradient_tolerance &&
          report.kinetic_energy <= options.kinetic_tolerance * energy_scale) {
        finish(DynamicsStatus::Converged, "gradient and kinetic energy below tolerance");
        break;
      }
      if (result.steps % std::max(options.rebase_interval, 1) == 0) {
        Eigen::VectorXd v = second_order ? Eigen::VectorXd(y.tail(n)) : Eigen::VectorXd();
        objective.rebase(second_order ? &v : nullptr);
        evaluator.sync();
        ++result.rebases;
        const Eigen::VectorXd before = y;
        y.head(n) = objective.get();
        if (second_order) y.tail(n) = v;
        weights = objective.gradient_weights();
        last_good = y;
        if (y == before) continue;  // nothing was re-expressed: no restart needed
        as_eigen(integrator.y.get()) = y;
        as_eigen(integrator.yp.get()) = system.consistent_derivatives(y);
        void* m = integrator.ida.get();
        check_sundials(IDAReInit(m, t, integrator.y.get(), integrator.yp.get()), "IDAReInit");
        check_sundials(IDASetInitStep(m, h), "IDASetInitStep");
      }
    }
    // Leave the objective at the last accepted state.
    evaluator.move_to(y.head(n));
  }

  result.time = report.time;
  result.energy = objective.energy();
  result.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
  result.kinetic_energy = kinetic(y);
  if (result.status != DynamicsStatus::NonFinite)
    result.stable = is_positive_definite(system.cholesky(), objective.hessian());
  result.factorizations =
      estimator.stats().factorizations + system.cholesky().stats().factorizations;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace xshell
