#include "integrators/dynamics/ida_dynamics.hpp"

#include <ida/ida.h>
#include <ida/ida_ls.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/dynamics/damping_choice.hpp"
#include "integrators/dynamics/ida_endgame.hpp"
#include "integrators/dynamics/ida_step_cap.hpp"
#include "integrators/dynamics/mass_and_damping.hpp"
#include "integrators/linear_algebra/sundials_handles.hpp"
#include "integrators/newton/newton.hpp"

namespace xshell {

namespace {

// A step shorter than this fraction of the simulated time means the
// integrator is creeping towards a barrier (configurations it cannot
// evaluate) and no longer advances time in floating point.
constexpr double kStagnantStepRatio = 1e-12;

// IDA and everything it owns; declaration order = construction order, the
// context first so that it is destroyed last. The DynamicsSystem (the
// linear solver's backend) must outlive this object.
struct IdaIntegrator {
  SunContext context;
  NVector y, yp, atol, id;
  SunMatrix placeholder;
  SunLinearSolver linear_solver;
  IdaMemory ida;
  std::string last_message;

  IdaIntegrator(DynamicsSystem& system, const DynamicsOptions& options, const Eigen::VectorXd& y0,
                const Eigen::VectorXd& yp0, const Eigen::VectorXd& absolute_tolerances) {
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
    // The gradient flow at BDF orders 3-5 (not A-stable) let the energy rise
    // by 1e-6 of its drop while a column buckled; orders 1-2 do not.
    const int order = system.form() == DynamicsForm::FirstOrder ? std::min(2, options.max_order)
                                                                : options.max_order;
    check_sundials(IDASetMaxOrd(m, order), "IDASetMaxOrd");
    if (options.suppress_velocity && size > system.unknowns()) {
      id = make_serial_vector(size, context);
      Eigen::Map<Eigen::VectorXd> ids = as_eigen(id.get());
      ids.head(system.unknowns()).setOnes();
      ids.tail(size - system.unknowns()).setZero();
      check_sundials(IDASetId(m, id.get()), "IDASetId");
      check_sundials(IDASetSuppressAlg(m, SUNTRUE), "IDASetSuppressAlg");
    }
    check_sundials(IDASetEtaMax(m, options.eta_max), "IDASetEtaMax");
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

}  // namespace

namespace {

// Dimensionless size of a unit of every unknown: the gradient weights have
// the unknowns' units over an energy, so w_i / min_j w_j is 1 for the
// unknowns measured in the smallest units (angles for the linkage) and the
// length scale for the others (positions). Tolerances and the rebase
// distance are multiples of it.
Eigen::VectorXd unknown_scales(const Eigen::VectorXd& weights) {
  const Eigen::VectorXd w = weights.cwiseAbs();
  const double smallest = w.size() > 0 ? w.minCoeff() : 0.0;
  if (!(smallest > 0.0) || !w.allFinite()) return Eigen::VectorXd::Ones(w.size());
  return w / smallest;
}

// Root mean square of x / (rtol |y| + atol), IDA's error norm, over the
// first x.size() entries of y and atol.
using ConstRef = Eigen::Ref<const Eigen::VectorXd>;

double weighted_rms(const ConstRef& x, const ConstRef& y, const ConstRef& atol, double rtol) {
  const Eigen::Index m = x.size();
  if (m == 0) return 0.0;
  const Eigen::ArrayXd weight = rtol * y.head(m).array().abs() + atol.head(m).array();
  return std::sqrt((x.array() / weight).square().sum() / static_cast<double>(m));
}

// A first step for IDA from y and y'. IDA's own estimate is 0.5 / |y'|,
// over the components in the error test; with the velocities out of it
// (second order, suppress), that norm sees only q' = v, which is zero at
// rest. The step is then sized from the motion of q: v h and a h^2 / 2
// (a = v') half the error test's tolerance. 0: no estimate.
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

}  // namespace

DynamicsResult solve_dynamics(Objective& objective, const DynamicsOptions& options,
                              const DynamicsCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  DynamicsResult result;
  const Eigen::Index n = objective.size();
  if (n == 0) {
    result.status = SolveStatus::Converged;
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
  DampingChoice choice = choose_damping(options, estimator, H0, mass);
  long extra_factorizations = 0;
  result.damping = choice.c;
  result.stiffness_damping = choice.damping.stiffness_coefficient;
  DynamicsSystem system(evaluator, options.form, mass, choice.damping);
  const bool second_order = options.form == DynamicsForm::SecondOrder;

  // Initial state: at rest, or moving with the overdamped velocity.
  Eigen::VectorXd y(system.size());
  y.head(n) = objective.get();
  if (second_order) y.tail(n).setZero();
  const bool slow_start = second_order && options.start == DynamicsStart::SlowManifold;
  Eigen::VectorXd weights = objective.gradient_weights();
  const Eigen::VectorXd scales =
      options.scaled_tolerances ? unknown_scales(weights) : Eigen::VectorXd::Ones(n);
  double relative_tolerance = options.relative_tolerance, tolerance_scale = 1.0;
  auto absolute_tolerances = [&] {
    Eigen::VectorXd atol(system.size());
    atol.head(n) = tolerance_scale * options.absolute_tolerance * scales;
    if (second_order) atol.tail(n) = atol.head(n) * system.damping().rate;
    return atol;
  };
  const double energy0 = objective.energy();
  DynamicsReport report;
  report.energy = energy0;
  report.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
  auto kinetic = [&](const Eigen::VectorXd& state) {
    return second_order ? 0.5 * state.tail(n).dot(mass.cwiseProduct(state.tail(n))) : 0.0;
  };
  const bool moving = std::isfinite(report.energy) && std::isfinite(report.gradient_measure) &&
                      report.gradient_measure > options.gradient_tolerance;
  // From an indefinite Hessian (choice.unstable) the slow manifold does not
  // attract along the unstable modes, and -C^-1 grad E is large along the
  // nearly undamped ones: such starts stay at rest.
  bool on_slow_manifold = false;
  if (slow_start && moving && !choice.unstable && !choice.zero_mode) {
    const double inertia =
        options.start_time > 0.0 ? system.damping().rate / options.start_time : 0.0;
    try {
      Eigen::VectorXd v = system.overdamped_velocity(0.0, inertia);
      // The overdamped velocity is the linear model's at the start. Along a
      // (nearly) zero mode, such as the free arm of a tee under gravity, it
      // is huge: it would carry the unknowns far beyond the model's reach
      // within one time constant (1 / rate), and the run would start with a
      // kinetic energy thousands of times the energy there is to release.
      // The velocity is scaled down to move at most start_reach (in units
      // of unknown_scales) in one time constant.
      const double reach = v.cwiseQuotient(scales).cwiseAbs().maxCoeff() / system.damping().rate;
      if (reach > options.start_reach) v *= options.start_reach / reach;
      if (v.allFinite()) {
        y.tail(n) = v;
        on_slow_manifold = true;
      }
    } catch (const std::runtime_error&) {
      // C + M/T not positive definite after all: start at rest.
    }
    report.kinetic_energy = kinetic(y);
  }
  if (callbacks.on_step) callbacks.on_step(report);
  auto finish = [&](SolveStatus status, std::string reason) {
    result.status = status;
    result.reason = std::move(reason);
  };

  if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure)) {
    finish(SolveStatus::NonFinite, "energy or gradient not finite at the start");
  } else if (report.gradient_measure <= options.gradient_tolerance) {
    finish(SolveStatus::Converged, "in equilibrium at the start");
  } else {
    const Eigen::VectorXd yp0 = system.consistent_derivatives(y, 0.0);
    IdaIntegrator integrator(system, options, y, yp0, absolute_tolerances());
    const bool q_only = second_order && options.suppress_velocity;
    if (options.initial_step <= 0.0) {
      // IDA's own first step is h = 0.5 / |y'|_WRMS (its rule for a distant
      // output time), which sees nothing of a start at rest when the
      // velocities are out of the error test; on the slow manifold, it is
      // sized for a fast layer that this start does not have: begin
      // start_step times longer.
      double h0 = first_step(y, yp0, absolute_tolerances(), relative_tolerance, n, q_only);
      if (on_slow_manifold && options.start_step > 1.0) h0 *= options.start_step;
      if (h0 > 0.0) check_sundials(IDASetInitStep(integrator.ida.get(), h0), "IDASetInitStep");
    }
    auto accumulate_stats = [&] {
      long value = 0;
      void* m = integrator.ida.get();
      IDAGetNumResEvals(m, &value);
      result.residual_evaluations += value;
      IDAGetNumErrTestFails(m, &value);
      result.error_test_failures += value;
      IDAGetNumNonlinSolvConvFails(m, &value);
      result.convergence_failures += value;
    };
    // Rayleigh damping from the Hessian at the current configuration.
    auto refreshed_damping = [&]() {
      const Eigen::SparseMatrix<double>& H = objective.hessian();
      if (options.refresh_damping >= 2) {
        const ModeEstimate warm = choice.modes;
        choice = choose_damping(options, estimator, H, mass, &warm);
        result.damping = choice.c;
        return choice.damping;
      }
      Damping d = system.damping();
      const double b = d.stiffness_coefficient;
      if (!(b > 0.0)) return d;
      const Eigen::VectorXd shift = (d.mass_coefficient / b) * mass;
      d.stiffness = H;
      if (estimator.factorize(H, &shift) != FactorizationStatus::PositiveDefinite) {
        const ShiftedFactorization f = factorize_with_shift(estimator, H, mass, options.shift);
        d.mass_coefficient = b * f.shift;
      }
      return d;
    };
    const double time_scale = 1.0 / system.damping().rate;
    const double total0 = report.energy + report.kinetic_energy;
    double last_total = total0;  // E + K at last_good
    Eigen::VectorXd last_good = y;
    double last_good_t = 0.0;
    // Restarts IDA at (time, y), the objective being at y's q, with
    // consistent derivatives and first step h_first (0: first_step's).
    auto restart_at = [&](double time, double h_first) {
      as_eigen(integrator.y.get()) = y;
      as_eigen(integrator.yp.get()) = system.consistent_derivatives(y, time);
      accumulate_stats();
      void* m = integrator.ida.get();
      check_sundials(IDAReInit(m, time, integrator.y.get(), integrator.yp.get()), "IDAReInit");
      as_eigen(integrator.atol.get()) = absolute_tolerances();
      check_sundials(IDASVtolerances(m, relative_tolerance, integrator.atol.get()),
                     "IDASVtolerances");
      if (!(h_first > 0.0))
        h_first = first_step(y, as_eigen(integrator.yp.get()), as_eigen(integrator.atol.get()),
                             relative_tolerance, n, q_only);
      check_sundials(IDASetInitStep(m, h_first), "IDASetInitStep");
    };
    double t = 0.0;
    // Rejects the step of length h just taken: IDA restarts from last_good
    // with half of it (at order 1, backward Euler, as every restart).
    // Returns false, the run finished, when that step would be stagnant.
    auto retry_shorter = [&](double h, const std::string& why) {
      ++result.rejected_steps;
      y = last_good;
      t = last_good_t;
      if (0.5 * h <= kStagnantStepRatio * t) {  // the objective is moved to y below the loop
        finish(SolveStatus::IntegratorFailed,
               why + " even for steps of " + scientific(0.5 * h) + " at t = " + scientific(t));
        return false;
      }
      if (evaluator.move_to(y.data()) != 0) {
        evaluator.rethrow_if_fatal();
        finish(SolveStatus::IntegratorFailed,
               "the objective rejected an accepted state: " + evaluator.last_message());
        return false;
      }
      restart_at(t, 0.5 * h);
      return true;
    };
    Eigen::VectorXd rebased_at = y.head(n);
    Eigen::VectorXd refreshed_at = y.head(n);
    long last_rebase = 0;
    bool endgame = false;
    // After a K that was not positive definite, steps as long are not tried
    // again for a while (definite_step_cap.hpp). The cap is set as the
    // factorization fails, so that IDA's next step obeys it.
    DefiniteStepCap step_cap;
    // An end game that does not converge hands back to the dynamics, which
    // then waits for steps endgame_growth times longer, or a gradient
    // endgame_growth times smaller, before the next (both triggers back off).
    double endgame_backoff = 1.0;
    const bool endgame_on = options.endgame_steps > 0.0;
    if (options.cap_indefinite_steps)
      system.on_indefinite([&step_cap, &integrator](double cj) {
        IDASetMaxStep(integrator.ida.get(), step_cap.on_failure(cj));
      });
    for (;;) {  // damped dynamics, then the end game; again if that fails
      for (;;) {
        if (callbacks.stop != nullptr && callbacks.stop->load()) {
          finish(SolveStatus::Interrupted, "stop flag raised");
          break;
        }
        if (result.iterations >= options.max_steps) {
          finish(SolveStatus::IterationLimit,
                 "no convergence in " + std::to_string(result.iterations) + " steps");
          break;
        }
        evaluator.clear_failures();
        const int flag = IDASolve(integrator.ida.get(), t + 1e10 * time_scale, &t,
                                  integrator.y.get(), integrator.yp.get(), IDA_ONE_STEP);
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
          // IDA gave up late in a run whose motion had died out (error tests
          // at the round-off floor of the residual): the end game can still
          // finish it from the last accepted state if that is a stable basin.
          if (endgame_on && t * system.damping().rate >= options.endgame_steps * endgame_backoff &&
              kinetic(y) <=
                  1e-6 * std::max(std::abs(energy0 - report.energy), std::abs(report.energy))) {
            evaluator.move_to(y.head(n));
            endgame = is_positive_definite(estimator, objective.hessian());
          }
          break;
        }
        // Lift the step cap once steps under it kept K positive definite.
        if (step_cap.on_step())
          check_sundials(IDASetMaxStep(integrator.ida.get(), 0.0), "IDASetMaxStep");
        double h = 0.0;
        IDAGetLastStep(integrator.ida.get(), &h);
        y = as_eigen(integrator.y.get());
        // IDA's last Newton correction lands on a y it never evaluated. When
        // that y is invalid (a rod's terminal edge through its joint, say),
        // the step is taken again, shorter, as a rejected step. The energy
        // there comes from the same pass as the move.
        double step_energy = 0.0;
        if (evaluator.energy_at(y.data(), &step_energy) != 0) {
          evaluator.rethrow_if_fatal();
          if (!retry_shorter(
                  h, "the objective rejects the accepted state (" + evaluator.last_message() + ")"))
            break;
          continue;
        }
        ++result.iterations;
        IDAGetLastOrder(integrator.ida.get(), &report.order);
        report.step = result.iterations;
        report.time = t;
        report.step_size = h;
        report.energy = step_energy;
        report.kinetic_energy = kinetic(y);
        report.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
        const double total = report.energy + report.kinetic_energy;
        if (options.dissipation_guard > 0.0 && std::isfinite(total) &&
            total - last_total > options.dissipation_guard * std::max(total0 - last_total, 0.0) +
                                     1e-12 * std::abs(report.energy)) {
          // E + K rose: the step is taken again (see DynamicsOptions).
          --result.iterations;
          if (!retry_shorter(h, "E + K rises")) break;
          continue;
        }
        if (callbacks.on_step) callbacks.on_step(report);
        if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure) ||
            !y.allFinite()) {
          finish(SolveStatus::NonFinite,
                 "non-finite state after step " + std::to_string(result.iterations));
          y = last_good;
          break;
        }
        if (h <= kStagnantStepRatio * t) {
          const bool nonfinite = evaluator.last_failure() == EvaluationFailure::NonFinite;
          finish(nonfinite ? SolveStatus::NonFinite : SolveStatus::IntegratorFailed,
                 "step size " + scientific(h) + " stagnant at t = " + scientific(t) +
                     (evaluator.last_message().empty() ? "" : ": " + evaluator.last_message()));
          break;
        }
        // The end game: the motion has died out as far as IDA resolves it
        // and its steps have grown to many time constants. Implicit Euler
        // with an infinite step is a Newton step, so the remaining steps are
        // taken at that limit (Newton with the energy line search), once the
        // Hessian is positive definite (a stable basin, not a saddle). The
        // check factorizes with the estimator's solver: IDA goes on with its
        // factorization of K when the Hessian is indefinite.
        if (endgame_on && h * system.damping().rate >= options.endgame_steps * endgame_backoff &&
            is_positive_definite(estimator, objective.hessian())) {
          last_good = y;
          endgame = true;
          break;
        }
        last_good = y;
        last_good_t = t;
        last_total = total;
        const double energy_scale =
            std::max(std::abs(energy0 - report.energy), std::abs(report.energy));
        const bool at_rest = report.kinetic_energy <= options.kinetic_tolerance * energy_scale;
        if (report.gradient_measure <= options.gradient_tolerance && at_rest) {
          finish(SolveStatus::Converged, "gradient and kinetic energy below tolerance");
          break;
        }
        // Settled near an equilibrium (see endgame_gradient_factor).
        if (endgame_on && options.endgame_gradient_factor > 0.0 && at_rest &&
            report.gradient_measure <=
                options.endgame_gradient_factor / endgame_backoff * options.gradient_tolerance) {
          endgame = true;
          break;
        }
        const bool blending = system.update_blend(t);
        if (!blending && options.refresh_distance > 0.0 &&
            options.damping_model == DampingModel::Rayleigh &&
            (y.head(n) - refreshed_at).cwiseQuotient(scales).cwiseAbs().maxCoeff() >
                options.refresh_distance) {
          // Stiffness-proportional damping from the Hessian here, blended in.
          refreshed_at = y.head(n);
          system.blend_damping(refreshed_damping(), t, options.blend_steps * h);
          ++result.refreshes;
        }
        const bool far = options.rebase_distance > 0.0 &&
                         ((y.head(n) - rebased_at).cwiseQuotient(scales).cwiseAbs().maxCoeff() >
                          options.rebase_distance);
        const bool due = options.rebase_interval > 0 &&
                         result.iterations - last_rebase >= options.rebase_interval;
        if (far || due) {
          last_rebase = result.iterations;
          Eigen::VectorXd v = second_order ? Eigen::VectorXd(y.tail(n)) : Eigen::VectorXd();
          objective.rebase(second_order ? &v : nullptr);
          evaluator.sync();
          ++result.rebases;
          const Eigen::VectorXd before = y;
          y.head(n) = objective.get();
          if (second_order) y.tail(n) = v;
          rebased_at = y.head(n);
          refreshed_at = y.head(n);
          weights = objective.gradient_weights();
          last_good = y;
          last_total = report.energy + kinetic(y);  // v re-expressed
          bool restart = !(y == before);
          if (options.refresh_damping > 0 && options.damping_model == DampingModel::Rayleigh) {
            system.set_damping(refreshed_damping());
            restart = true;
          } else if (options.refresh_damping > 0 && choice.unstable) {
            choice = choose_damping(options, estimator, objective.hessian(), mass);
            system.set_damping(choice.damping);
            restart = true;
          }
          if (!restart) continue;  // nothing was re-expressed: no restart needed
          restart_at(t, options.restart_step > 0 ? h * options.restart_step : 0.0);
        }
      }
      // Leave the objective at the last accepted state.
      evaluator.move_to(y.head(n));
      if (!endgame) break;
      const int max_iterations = static_cast<int>(std::min<long>(
          options.endgame_iterations, std::max<long>(1, options.max_steps - result.iterations)));
      if (second_order) y.tail(n).setZero();  // the infinite step ends at rest
      const NewtonResult polished =
          run_endgame(objective, options, max_iterations, callbacks, result.iterations, report);
      result.iterations += polished.iterations;
      result.endgame_steps += polished.iterations;
      extra_factorizations += polished.factorizations;
      evaluator.sync();
      y.head(n) = objective.get();
      weights = objective.gradient_weights();
      if (polished.status == SolveStatus::IterationLimit && result.iterations < options.max_steps &&
          options.endgame_growth > 1.0) {
        // Handed over too early (far from the equilibrium, in a region
        // where H happens to be positive definite): the dynamics go on at
        // rest from where the end game stopped, its energy lower than at
        // the hand-over (the line search only lowers it).
        ++result.endgame_fallbacks;
        endgame = false;
        endgame_backoff *= options.endgame_growth;
        last_good = y;
        last_good_t = t;
        last_total = polished.energy;
        rebased_at = y.head(n);
        refreshed_at = y.head(n);
        restart_at(t, 0.0);
        continue;
      }
      finish(endgame_status(polished), endgame_reason(polished));
      break;
    }
    accumulate_stats();
    system.on_indefinite(nullptr);
  }

  result.time = report.time;
  result.energy = objective.energy();
  result.gradient_measure = weighted_max_norm(weights, evaluator.gradient());
  result.kinetic_energy = kinetic(y);
  if (result.status != SolveStatus::NonFinite)
    result.stable = is_positive_definite(estimator, objective.hessian());
  result.factorizations = estimator.stats().factorizations +
                          system.cholesky().stats().factorizations + extra_factorizations;
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace xshell
