#include "integrators/deployment/constrained_newton.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"
#include "integrators/newton/descent_step.hpp"

namespace xshell {

namespace {

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  return text;
}

struct Backtrack {
  bool accepted = false;
  int trials = 0, rejected = 0;
};

// Armijo backtracking from q0 along p (as descent_step.hpp, whose options
// it takes, but for a given direction) on the exact penalty merit
//   phi(q) = E(q) + mu |a . q - A|:
// the energy itself on the constraint's plane (where both steps descend:
// g . p = -r^T K^-1 r < 0), and from a start off the plane, where the
// energy may have to rise to restore the constraint, a merit that the step
// decreases when mu > max(|tau|, g . p / |c|) (here twice that): its
// slope is g . p - mu |c| < 0. Accepts phi(q0 + t p) <= phi(q0) + c1 t
// min(slope, 0) (+ round-off slack), or, in the end game, the full step
// when it lowers |diag(w) (g - tau a)|. On failure the objective is back at q0.
Backtrack backtrack(ObjectiveEvaluator& evaluator, const AverageConstraint& constraint,
                    double target, double mu, const Eigen::VectorXd& q0, double e0,
                    const Eigen::VectorXd& p, double slope, const Eigen::VectorXd& w, double r0,
                    const DescentStepOptions& options) {
  Backtrack result;
  auto merit = [&](double energy, const Eigen::VectorXd& q) {
    return energy + mu * std::abs(constraint.value(q) - target);
  };
  const double phi0 = merit(e0, q0);
  double t = 1.0;
  for (int k = 0; k <= options.max_backtracks; ++k, t *= options.shrink) {
    const Eigen::VectorXd trial = q0 + t * p;
    if (trial == q0) break;
    ++result.trials;
    double energy = 0.0;
    try {
      energy = evaluator.energy_at(trial);
    } catch (const std::domain_error& e) {
      evaluator.record(EvaluationFailure::InvalidConfiguration, e.what());
      ++result.rejected;
      continue;
    }
    if (!std::isfinite(energy)) {
      evaluator.record(EvaluationFailure::NonFinite, "the energy is not finite");
      ++result.rejected;
      continue;
    }
    const double slack = options.energy_noise * std::abs(e0);
    if (merit(energy, trial) <=
        phi0 + options.sufficient_decrease * t * std::min(slope, 0.0) + slack) {
      result.accepted = true;
      return result;
    }
    if (k == 0 && std::abs(energy - e0) <= options.endgame_energy_change * std::abs(e0)) {
      const Eigen::VectorXd g = evaluator.gradient();
      if (g.allFinite() && (w.array() * constraint.projected(g).array()).matrix().norm() < r0) {
        result.accepted = true;
        return result;
      }
    }
  }
  evaluator.move_to(q0);
  return result;
}

}  // namespace

struct ConstrainedNewtonSolver::Impl {
  ObjectiveEvaluator evaluator;
  CholeskySolver full;     // H, for the Schur complement
  CholeskySolver reduced;  // B^T H B, for the fallback and the stability test
  explicit Impl(Objective& objective) : evaluator(objective) {}
  long factorizations() const {
    return full.stats().factorizations + reduced.stats().factorizations;
  }
};

ConstrainedNewtonSolver::ConstrainedNewtonSolver(Objective& objective,
                                                 const AverageConstraint& constraint,
                                                 NewtonOptions options)
    : objective_(objective),
      constraint_(constraint),
      options_(options),
      impl_(std::make_unique<Impl>(objective)) {
  if (objective.size() != constraint.size())
    throw std::invalid_argument("constrained Newton: the constraint does not fit the objective");
}

ConstrainedNewtonSolver::~ConstrainedNewtonSolver() = default;

ConstrainedNewtonResult ConstrainedNewtonSolver::solve(double target,
                                                       const NewtonCallbacks& callbacks) {
  const Clock::time_point start = Clock::now();
  Impl& s = *impl_;
  const long factorizations_before = s.factorizations();
  const Eigen::VectorXd& a = constraint_.coefficients();
  ConstrainedNewtonResult result;
  s.evaluator.sync();
  s.evaluator.clear_failures();
  const Eigen::VectorXd mass = objective_.mass();
  DescentStepOptions descent;
  descent.max_step = options_.max_step;
  auto measure = [&](const Eigen::VectorXd& w, const Eigen::VectorXd& g) {
    return weighted_max_norm(w, constraint_.projected(g));
  };

  NewtonReport report;
  report.energy = objective_.energy();
  report.gradient_measure = measure(objective_.gradient_weights(), s.evaluator.gradient());
  if (callbacks.on_iteration) callbacks.on_iteration(report);
  bool stagnant = false;
  // Round-off floor: the measure has not halved for kStalledIterations
  // iterations while the energy no longer changes.
  constexpr int kStalledIterations = 5;
  double best_measure = report.gradient_measure;
  int stalled = 0;

  int iteration = 0;
  for (;;) {
    for (;; ++iteration) {
      result.iterations = iteration;
      result.energy = report.energy;
      result.gradient_measure = report.gradient_measure;
      const double residual = target - constraint_.value(objective_.get());
      if (!std::isfinite(report.energy) || !std::isfinite(report.gradient_measure)) {
        result.status = NewtonStatus::NonFinite;
        result.reason =
            "energy or gradient not finite after " + std::to_string(iteration) + " iterations";
        break;
      }
      if (report.gradient_measure <= options_.gradient_tolerance &&
          std::abs(residual) <= constraint_tolerance) {
        result.status = NewtonStatus::Converged;
        result.reason = "gradient measure " + scientific(report.gradient_measure) + " <= tolerance";
        break;
      }
      if (stagnant || stalled >= kStalledIterations) {
        result.status = NewtonStatus::LineSearchFailed;
        result.reason = std::string("stagnation: ") +
                        (stagnant ? "the step fell below the scaled step tolerance"
                                  : "no progress in " + std::to_string(kStalledIterations) +
                                        " iterations at a constant energy") +
                        " at gradient measure " + scientific(report.gradient_measure) +
                        " (round-off floor above the tolerance?)";
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
      const long factorizations_at_start = s.factorizations();
      objective_.rebase();
      s.evaluator.sync();
      const Eigen::VectorXd q0 = objective_.get();
      const Eigen::VectorXd w = objective_.gradient_weights();
      // The Hessian first: the linkage's pass gives the gradient with it.
      const Eigen::SparseMatrix<double>& H = objective_.hessian();
      const Eigen::VectorXd g0 = s.evaluator.gradient();
      const double e0 = objective_.energy();
      const double c = target - constraint_.value(q0);

      Eigen::VectorXd p;
      double tau = 0.0;  // the step's multiplier
      report.shifted = false;
      report.shift = 0.0;
      const FactorizationStatus status = s.full.factorize(H);
      if (status == FactorizationStatus::NonFinite) {
        result.status = NewtonStatus::NonFinite;
        result.reason = "the Hessian is not finite";
        break;
      }
      if (status == FactorizationStatus::PositiveDefinite) {
        // Schur complement: two solves with the one factorization.
        const Eigen::VectorXd x1 = s.full.solve(g0), x2 = s.full.solve(a);
        tau = (c + a.dot(x1)) / a.dot(x2);
        p = tau * x2 - x1;
        ++result.schur_iterations;
      } else {
        const ShiftedFactorization f = factorize_with_shift(
            s.reduced, constraint_.reduce(H), constraint_.reduce_diagonal(mass), options_.shift);
        if (f.status != FactorizationStatus::PositiveDefinite) {
          result.status = f.status == FactorizationStatus::NonFinite
                              ? NewtonStatus::NonFinite
                              : NewtonStatus::LinearSolverFailed;
          result.reason =
              "the constrained Hessian could not be factorized even with the largest shift";
          break;
        }
        // Restore the constraint by the minimal shift d0, then Newton on the
        // plane with the gradient extrapolated there: g0 + H d0.
        const Eigen::VectorXd d0 = (c / a.squaredNorm()) * a;
        const Eigen::VectorXd g_shifted = c != 0.0 ? Eigen::VectorXd(g0 + H * d0) : g0;
        p = constraint_.expand(-s.reduced.solve(constraint_.restrict(g_shifted))) + d0;
        tau = constraint_.multiplier(g0);
        report.shifted = f.shifted;
        report.shift = f.shift;
        ++result.null_space_iterations;
      }
      const double length = p.norm();
      if (!std::isfinite(length)) {
        result.status = NewtonStatus::NonFinite;
        result.reason = "the Newton step is not finite";
        break;
      }
      if (length > options_.max_step) p *= options_.max_step / length;

      const double r0 = (w.array() * constraint_.projected(g0).array()).matrix().norm();
      Backtrack step;
      try {
        const double gp = g0.dot(p);
        const double mu =
            c == 0.0 ? 0.0 : 2.0 * std::max(std::abs(tau), std::max(gp, 0.0) / std::abs(c));
        step = backtrack(s.evaluator, constraint_, target, mu, q0, e0, p, gp - mu * std::abs(c), w,
                         r0, descent);
      } catch (...) {
        objective_.set(q0);
        throw;
      }
      if (!step.accepted) {
        objective_.set(q0);
        s.evaluator.sync();
        const bool all_rejected = step.trials > 0 && step.rejected == step.trials;
        result.status = all_rejected && s.evaluator.last_failure() == EvaluationFailure::NonFinite
                            ? NewtonStatus::NonFinite
                            : NewtonStatus::LineSearchFailed;
        result.reason = all_rejected ? "the objective failed at every trial point: " +
                                           s.evaluator.last_message()
                                     : "no energy decrease along the constrained Newton step";
        break;
      }
      const Eigen::VectorXd q = objective_.get();
      report.iteration = iteration + 1;
      report.energy = objective_.energy();
      report.gradient_measure = measure(w, s.evaluator.gradient());
      report.step_norm = (q - q0).lpNorm<Eigen::Infinity>();
      report.energy_line_search = true;
      stagnant = ((q - q0).array().abs() / (1.0 + q.array().abs())).maxCoeff() <=
                 options_.scaled_step_tolerance;
      if (report.gradient_measure < 0.5 * best_measure) {
        best_measure = report.gradient_measure;
        stalled = 0;
      } else if (std::abs(report.energy - e0) <= 1e-13 * std::abs(e0)) {
        ++stalled;
      }
      report.factorizations = s.factorizations() - factorizations_at_start;
      report.seconds = seconds_since(iteration_start);
      if (callbacks.on_iteration) callbacks.on_iteration(report);
    }

    if (result.status != NewtonStatus::NonFinite)
      result.stable = is_positive_definite(s.reduced, constraint_.reduce(objective_.hessian()));
    if (!result.converged() || result.stable || result.saddle_escapes >= max_saddle_escapes) break;
    // A saddle: leave it downhill along negative curvature, then iterate on.
    const Clock::time_point escape_start = Clock::now();
    const long factorizations_at_escape = s.factorizations();
    const Eigen::VectorXd q_saddle = objective_.get();
    if (!escape_saddle(mass)) break;
    ++result.saddle_escapes;
    ++iteration;
    s.evaluator.sync();
    report.iteration = iteration;
    report.energy = objective_.energy();
    report.gradient_measure = measure(objective_.gradient_weights(), s.evaluator.gradient());
    report.step_norm = (objective_.get() - q_saddle).lpNorm<Eigen::Infinity>();
    report.shifted = true;
    report.factorizations = s.factorizations() - factorizations_at_escape;
    report.seconds = seconds_since(escape_start);
    if (callbacks.on_iteration) callbacks.on_iteration(report);
    stagnant = false;
    best_measure = report.gradient_measure;
    stalled = 0;
    result.stable = false;
  }  // saddle escapes
  const Eigen::VectorXd g = objective_.gradient();
  result.multiplier = constraint_.multiplier(g);
  result.constraint_residual = target - constraint_.value(objective_.get());
  result.factorizations = s.factorizations() - factorizations_before;
  result.seconds = seconds_since(start);
  return result;
}

bool ConstrainedNewtonSolver::escape_saddle(const Eigen::VectorXd& mass) {
  Impl& s = *impl_;
  const Eigen::SparseMatrix<double> Hz = constraint_.reduce(objective_.hessian());
  const Eigen::VectorXd Mz = constraint_.reduce_diagonal(mass);
  const ShiftedFactorization f = factorize_with_shift(s.reduced, Hz, Mz, options_.shift);
  if (f.status != FactorizationStatus::PositiveDefinite) return false;
  // Inverse iteration with Hz + shift Mz: converges to the eigenvector of
  // the most negative eigenvalue of (Hz, Mz), the one nearest -shift.
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd x(Hz.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = uniform(rng);
  for (int k = 0; k < 30; ++k) {
    x = s.reduced.solve(Eigen::VectorXd(Mz.cwiseProduct(x)));
    x /= std::sqrt(x.dot(Mz.cwiseProduct(x)));
  }
  if (!x.allFinite() || !(x.dot(Hz * x) < 0.0)) return false;
  Eigen::VectorXd d = constraint_.expand(x);
  Eigen::Index largest = 0;
  d.cwiseAbs().maxCoeff(&largest);
  d /= d[largest];  // largest entry +1: a deterministic side
  const Eigen::VectorXd q0 = objective_.get();
  const double e0 = objective_.energy();
  double best_t = 0.0, best_e = e0;
  for (double t = 1e-3 * std::max(1.0, q0.lpNorm<Eigen::Infinity>()), k = 0; k < 16;
       t *= 2.0, ++k) {
    double e = 0.0;
    try {
      objective_.set(q0 + t * d);
      e = objective_.energy();
    } catch (const std::domain_error&) {
      break;
    }
    if (!std::isfinite(e)) break;
    if (e < best_e) {
      best_e = e;
      best_t = t;
    } else if (best_t > 0.0) {
      break;
    }
  }
  objective_.set(q0 + best_t * d);
  return best_t > 0.0;
}

Eigen::VectorXd ConstrainedNewtonSolver::tangent() {
  Impl& s = *impl_;
  const Eigen::VectorXd& a = constraint_.coefficients();
  const Eigen::SparseMatrix<double>& H = objective_.hessian();
  if (s.full.factorize(H) == FactorizationStatus::PositiveDefinite) {
    const Eigen::VectorXd x = s.full.solve(a);
    return x / a.dot(x);
  }
  const ShiftedFactorization f =
      factorize_with_shift(s.reduced, constraint_.reduce(H),
                           constraint_.reduce_diagonal(objective_.mass()), options_.shift);
  if (f.status != FactorizationStatus::PositiveDefinite) return {};
  const Eigen::VectorXd t0 = a / a.squaredNorm();
  const Eigen::VectorXd Ht0 = H * t0;
  return t0 - constraint_.expand(s.reduced.solve(constraint_.restrict(Ht0)));
}

}  // namespace xshell
