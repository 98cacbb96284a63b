#include "mass_and_damping.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace xshell {

Eigen::VectorXd fictitious_mass(const Eigen::SparseMatrix<double>& H, double floor_ratio) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(H.rows());
  for (int j = 0; j < H.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, j); it; ++it)
      m[it.row()] += std::abs(it.value());
  const double largest = m.size() > 0 ? m.maxCoeff() : 0.0;
  if (!(largest > 0.0) || !std::isfinite(largest)) return Eigen::VectorXd::Ones(H.rows());
  return m.cwiseMax(floor_ratio * largest);
}

LowestMode estimate_lowest_mode(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H,
                                const Eigen::VectorXd& mass, int iterations,
                                const ShiftOptions& shift) {
  LowestMode mode;
  const ShiftedFactorization f = factorize_with_shift(solver, H, mass, shift);
  mode.shifted = f.shifted;
  mode.shift = f.shift;
  mode.factorizations = f.factorizations;
  if (f.status != FactorizationStatus::PositiveDefinite) return mode;

  // A fixed pseudo-random start: not orthogonal to the lowest mode in practice.
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd x(H.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = uniform(rng);
  auto m_normalize = [&](Eigen::VectorXd& y) { y /= std::sqrt(y.dot(mass.cwiseProduct(y))); };
  m_normalize(x);
  for (int k = 0; k < iterations; ++k) {
    x = solver.solve(Eigen::VectorXd(mass.cwiseProduct(x)));
    m_normalize(x);
    ++mode.iterations;
  }
  mode.eigenvalue = x.dot(H * x) / x.dot(mass.cwiseProduct(x));
  mode.ok = std::isfinite(mode.eigenvalue);
  mode.vector = std::move(x);
  return mode;
}

ModeEstimate estimate_modes(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H,
                            const Eigen::VectorXd& mass, int iterations, const ShiftOptions& shift,
                            int max_unstable, const ModeEstimate* warm, double zero_floor,
                            double converged_change) {
  ModeEstimate estimate;
  LowestMode& mode = estimate.lowest;
  const ShiftedFactorization f = factorize_with_shift(solver, H, mass, shift);
  mode.shifted = f.shifted;
  mode.shift = f.shift;
  mode.factorizations = f.factorizations;
  estimate.certified_shift = f.shift;
  if (f.status != FactorizationStatus::PositiveDefinite) return estimate;

  auto m_dot = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.dot(mass.cwiseProduct(b));
  };
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Eigen::VectorXd> found;  // unstable modes, M-orthonormal
  auto iterate = [&](LowestMode& m, const Eigen::VectorXd* start) {
    Eigen::VectorXd x(H.rows());
    if (start != nullptr && start->size() == x.size()) {
      x = *start;
    } else {
      for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = uniform(rng);
    }
    auto project = [&](Eigen::VectorXd& y) {
      for (const Eigen::VectorXd& u : found) y -= m_dot(u, y) * u;
      y /= std::sqrt(m_dot(y, y));
    };
    project(x);
    double theta_before = 0.0;
    for (int k = 0; k < iterations; ++k) {
      Eigen::VectorXd y = solver.solve(Eigen::VectorXd(mass.cwiseProduct(x)));
      // theta = x'M (H + sM)^-1 M x, the Rayleigh quotient of the iteration's
      // operator (1 / (lambda + s) at an eigenvector), from the solve made.
      const double theta = m_dot(x, y);
      x = std::move(y);
      project(x);
      ++m.iterations;
      if (k > 0 && std::abs(theta - theta_before) < converged_change * std::abs(theta)) break;
      theta_before = theta;
    }
    m.eigenvalue = x.dot(H * x);
    m.ok = std::isfinite(m.eigenvalue);
    m.vector = std::move(x);
  };
  iterate(mode, warm != nullptr && warm->lowest.ok ? &warm->lowest.vector : nullptr);
  if (!mode.ok || mode.eigenvalue > zero_floor) {
    estimate.stable = mode;
    return estimate;
  }
  found.push_back(mode.vector);
  estimate.unstable_modes = 1;
  const Eigen::VectorXd* start = warm != nullptr && warm->stable.ok ? &warm->stable.vector : nullptr;
  for (int k = 1; k <= max_unstable; ++k) {
    LowestMode next;
    next.shifted = true;
    next.shift = f.shift;
    iterate(next, start);
    start = nullptr;
    if (!next.ok) break;
    if (next.eigenvalue > zero_floor) {
      estimate.stable = std::move(next);
      break;
    }
    found.push_back(next.vector);
    ++estimate.unstable_modes;
  }
  return estimate;
}

double automatic_damping(const LowestMode& mode, const Eigen::SparseMatrix<double>& H,
                         const Eigen::VectorXd& mass) {
  double trace = 0.0;
  for (Eigen::Index i = 0; i < H.rows(); ++i) trace += std::abs(H.coeff(i, i));
  const double floor = 1e-12 * trace / mass.sum();
  const double lambda = mode.ok ? std::max(std::abs(mode.eigenvalue), floor) : floor;
  const double c = 2.0 * std::sqrt(lambda);
  return c > 0.0 && std::isfinite(c) ? c : 1.0;
}

}  // namespace xshell
