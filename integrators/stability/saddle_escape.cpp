#include "integrators/stability/saddle_escape.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/deployment/path_predictor.hpp"
#include "integrators/stability/eigen_modes.hpp"

namespace xshell {

namespace {

// Below this fraction of |bias| |phi|, bias . phi is round-off: the mode
// moves no joint along the buckling direction.
constexpr double kNegligibleBias = 1e-8;
// Trials of the step: doublings while the energy falls, halvings while
// the first trial does not lower it.
constexpr int kMaxDoublings = 24;
constexpr int kMaxHalvings = 30;
// The difference step of D3E[d, d] (d's largest entry 1): the second
// difference's truncation error O(1e-6) against its round-off, about
// 1e-16 |g| / 1e-6.
constexpr double kBendStep = 1e-3;

// The escape's path: q0 + t d + t^2 w (w empty: the straight line).
Eigen::VectorXd path_point(const Eigen::VectorXd& q0, const Eigen::VectorXd& d,
                           const Eigen::VectorXd& w, double t) {
  return w.size() == 0 ? Eigen::VectorXd(q0 + t * d) : Eigen::VectorXd(q0 + t * d + t * t * w);
}

// The energy at path_point(q0, d, w, t), or +inf where the configuration
// is invalid.
double energy_along(Objective& objective, const Eigen::VectorXd& q0, const Eigen::VectorXd& d,
                    const Eigen::VectorXd& w, double t) {
  try {
    const double e = objective.set_and_energy(path_point(q0, d, w, t));
    return std::isfinite(e) ? e : INFINITY;
  } catch (const std::domain_error&) {
    return INFINITY;
  }
}

// The amplitude t > 0 of the lowest energy among the trials (0 when no
// trial fell below `floor`), with the objective left anywhere.
double best_amplitude(Objective& objective, const Eigen::VectorXd& q0, const Eigen::VectorXd& d,
                      const Eigen::VectorXd& w, double floor) {
  const double t0 = 1e-3 * std::max(1.0, q0.lpNorm<Eigen::Infinity>());
  double t = t0, best_t = 0.0, best_e = floor;
  for (int k = 0; k < kMaxHalvings && best_t == 0.0; ++k, t *= 0.5) {
    const double e = energy_along(objective, q0, d, w, t);
    if (e < best_e) best_e = e, best_t = t;
  }
  if (best_t != t0) return best_t;  // found by halving (or nothing found)
  for (int k = 0; k < kMaxDoublings; ++k) {
    const double e = energy_along(objective, q0, d, w, 2.0 * best_t);
    if (!(e < best_e)) break;
    best_e = e;
    best_t *= 2.0;
  }
  return best_t;
}

}  // namespace

Eigen::VectorXd signed_direction(const Eigen::VectorXd& phi, const Eigen::VectorXd& bias) {
  Eigen::VectorXd d = phi;
  Eigen::Index largest = 0;
  const double scale = d.cwiseAbs().maxCoeff(&largest);
  if (!(scale > 0.0)) return d;
  double sign = d[largest] > 0.0 ? 1.0 : -1.0;
  if (bias.size() == d.size()) {
    const double product = bias.dot(d);
    if (std::abs(product) > kNegligibleBias * bias.norm() * d.norm())
      sign = product > 0.0 ? 1.0 : -1.0;
  }
  return (sign / scale) * d;
}

NegativeMode negative_mode(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                           CholeskySolver& solver, const SaddleEscapeOptions& options) {
  NegativeMode out;
  EigenModesOptions modes;
  modes.count = 1;
  const EigenModes lowest = lowest_eigenmodes(H, mass, modes, &solver);
  if (!lowest.converged || lowest.values.size() < 1) return out;
  out.found = true;
  out.eigenvalue = lowest.values[0];
  const double mass_norm = mass.norm();
  const double scale = mass_norm > 0.0 ? H.norm() / mass_norm : 0.0;
  out.negative = out.eigenvalue < -options.relative_threshold * scale;
  out.vector = signed_direction(lowest.vectors.col(0), options.bias);
  return out;
}

double step_downhill(Objective& objective, const Eigen::VectorXd& direction,
                     const SaddleEscapeOptions& options, const Eigen::VectorXd& bend) {
  const Eigen::VectorXd q0 = objective.get();
  const double e0 = objective.energy();
  const double t =
      best_amplitude(objective, q0, direction, bend, e0 - options.energy_noise * std::abs(e0));
  objective.set(path_point(q0, direction, bend, t));
  return t;
}

Eigen::VectorXd third_derivative_along(Objective& objective, const Eigen::VectorXd& d) {
  return gradient_second_difference_or_empty(
      [&](const Eigen::VectorXd& x) {
        objective.set(x);
        return objective.gradient();
      },
      objective.get(), d, kBendStep);
}

Eigen::VectorXd bend_of_mode(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                             double eigenvalue, const Eigen::VectorXd& mode,
                             const Eigen::VectorXd& third, CholeskySolver& solver) {
  if (third.size() != H.rows() || !(eigenvalue < 0.0)) return {};
  const Eigen::VectorXd shift = -2.0 * eigenvalue * mass;
  if (solver.factorize(H, &shift) != FactorizationStatus::PositiveDefinite) return {};
  Eigen::VectorXd w = -0.5 * solver.solve(third);
  w -= (mode.dot(mass.cwiseProduct(w)) / mode.dot(mass.cwiseProduct(mode))) * mode;
  return w.allFinite() ? w : Eigen::VectorXd();
}

EscapeResult escape_saddle(Objective& objective, const Eigen::SparseMatrix<double>& H,
                           const Eigen::VectorXd& mass, CholeskySolver& solver,
                           const SaddleEscapeOptions& options) {
  EscapeResult out;
  out.saddle.energy = objective.energy();
  const NegativeMode mode = negative_mode(H, mass, solver, options);
  if (!mode.found) return out;
  out.saddle.lowest_eigenvalue = mode.eigenvalue;
  if (!mode.negative) {
    out.outcome = EscapeOutcome::NoNegativeCurvature;
    return out;
  }
  out.mode = mode.vector;
  const Eigen::VectorXd bend = bend_of_mode(H, mass, mode.eigenvalue, out.mode,
                                            third_derivative_along(objective, out.mode), solver);
  out.amplitude = step_downhill(objective, out.mode, options, bend);
  out.outcome = out.amplitude > 0.0 ? EscapeOutcome::Escaped : EscapeOutcome::NoDescent;
  return out;
}

}  // namespace xshell
