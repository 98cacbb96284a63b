#include "integrators/dynamics/damping_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace xshell {

namespace {

// C = c M: c as given, or critical damping of the slowest mode.
DampingChoice mass_proportional_damping(const DynamicsOptions& options, CholeskySolver& solver,
                                        const Eigen::SparseMatrix<double>& H,
                                        const Eigen::VectorXd& mass) {
  DampingChoice choice;
  double c = options.damping.coefficient;
  if (!(c > 0.0)) {
    const LowestMode mode =
        estimate_lowest_mode(solver, H, mass, options.damping.iterations, options.shift);
    choice.factorizations = mode.factorizations;
    choice.unstable = mode.shifted;
    c = automatic_damping(mode, H, mass);
  }
  choice.c = c;
  choice.damping.mass_coefficient = c;
  choice.damping.rate = 0.5 * c;
  return choice;
}

}  // namespace

DampingChoice choose_damping(const DynamicsOptions& options, CholeskySolver& solver,
                             const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                             const ModeEstimate* warm) {
  if (options.damping.model != DampingModel::Rayleigh)
    return mass_proportional_damping(options, solver, H, mass);
  // Rayleigh: C = b (H + mu M).
  DampingChoice choice;
  double trace = 0.0;
  for (Eigen::Index i = 0; i < H.rows(); ++i) trace += std::abs(H.coeff(i, i));
  const double floor =
      std::max(options.damping.mode_floor * trace / mass.sum(), std::numeric_limits<double>::min());
  choice.modes =
      estimate_modes(solver, H, mass, options.damping.iterations, options.shift, 4, warm, floor);
  const ModeEstimate& m = choice.modes;
  choice.factorizations = m.lowest.factorizations;
  double mu = 0.0, b = 0.0, omega = 0.0;
  if (!m.lowest.ok) {
    // Nothing known: mass-proportional damping with c = 1.
    choice.damping.mass_coefficient = 1.0;
    choice.damping.rate = 0.5;
    choice.c = 1.0;
    return choice;
  }
  if (m.lowest.eigenvalue > floor) {
    const double lambda = m.lowest.eigenvalue;
    mu = lambda;
    omega = std::sqrt(lambda);
    b = 1.0 / omega;
  } else {
    // Indefinite, or a zero mode (which round-off puts on either side of
    // zero): the damping rate comes from the lowest stable mode. With the
    // zero mode's own eigenvalue (the floor), b = 1 / sqrt(floor) would
    // overdamp every other mode into a creep.
    choice.unstable = m.lowest.eigenvalue < 0.0 && m.lowest.shifted;
    choice.zero_mode = !choice.unstable;
    const double negative = std::max(-m.lowest.eigenvalue, 0.0);
    const double lambda =
        m.stable.ok ? std::max(m.stable.eigenvalue, floor) : std::max(negative, floor);
    // An (almost) zero mode, such as a joint free to open at the start,
    // still gets damping C x = b mu M x: mu is at least a fraction of the
    // lowest stable eigenvalue, or the mode would move without bound.
    mu = std::max(
        (options.form == DynamicsForm::SecondOrder ? options.damping.unstable_margin : 2.0) *
            negative,
        options.damping.zero_mode_fraction * lambda);
    const Eigen::VectorXd shift = mu * mass;
    ++choice.factorizations;
    if (solver.factorize(H, &shift) != FactorizationStatus::PositiveDefinite)
      mu = std::max(mu, m.certified_shift);
    omega = std::sqrt(lambda);
    b = 2.0 * omega / (lambda + mu);
  }
  if (options.damping.coefficient > 0.0) {  // a given c: critical damping at lambda = c^2 / 4
    omega = 0.5 * options.damping.coefficient;
    b = 1.0 / omega;
    mu = std::max(mu, omega * omega);
  }
  choice.damping.mass_coefficient = b * mu;
  choice.damping.stiffness_coefficient = b;
  choice.damping.stiffness = H;
  choice.damping.rate = omega;
  choice.c = b * mu;
  return choice;
}

}  // namespace xshell
