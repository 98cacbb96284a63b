#include "integrators/dynamics/mass_and_damping.hpp"

#include <Eigen/Eigenvalues>
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

namespace {

// Rayleigh-Ritz on span(found, m.vector): the unstable vectors of an
// iteration stopped early still hold parts of the stable mode, which the
// projection against them took out of m.vector (a clustered test case: 1.90
// instead of 2.0). The Ritz value above the unstable ones restores it.
void refine_above(LowestMode& m, const std::vector<Eigen::VectorXd>& found,
                  const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass) {
  const Eigen::Index k = static_cast<Eigen::Index>(found.size());
  Eigen::MatrixXd V(H.rows(), k + 1);
  for (Eigen::Index j = 0; j < k; ++j) V.col(j) = found[static_cast<size_t>(j)];
  V.col(k) = m.vector;
  const Eigen::MatrixXd HV = H * V;
  const Eigen::MatrixXd h = V.transpose() * HV;
  const Eigen::MatrixXd mv = V.transpose() * mass.asDiagonal() * V;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(0.5 * (h + h.transpose()),
                                                                       0.5 * (mv + mv.transpose()));
  if (ritz.info() != Eigen::Success || !std::isfinite(ritz.eigenvalues()[k])) return;
  m.eigenvalue = ritz.eigenvalues()[k];
  m.vector = V * ritz.eigenvectors().col(k);
  m.vector /= std::sqrt(m.vector.dot(mass.cwiseProduct(m.vector)));
}

}  // namespace

namespace {

// Inverse iteration x <- (H + s M)^-1 M x with the factorization of
// H + s M in `solver`, each iterate M-orthogonal to the unstable modes
// found so far. Starts from a given vector or a pseudo-random one, from one
// generator for all the modes of an estimate.
class DeflatedInverseIteration {
 public:
  DeflatedInverseIteration(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H,
                           const Eigen::VectorXd& mass, int iterations, double shift,
                           double zero_floor, double converged_change)
      : solver_(solver),
        H_(H),
        mass_(mass),
        iterations_(iterations),
        shift_(shift),
        zero_floor_(zero_floor),
        converged_change_(converged_change) {}

  // Iterates into m (eigenvalue x'Hx, ok, vector; counts its iterations).
  // below_floor: stop as soon as the mode is known to be at or below
  // zero_floor. 1 / theta - s bounds the lowest eigenvalue of the deflated
  // problem from above, so once it is at or below the floor another unstable
  // or zero mode exists, and its exact value is not needed: only the lowest
  // mode's value and the lowest stable one's enter the damping. In a cluster
  // of zero modes (a linkage without supports: its rigid motions) the
  // iterations converge slowly, and the largest design spent 72 of 91 solves
  // on four such modes.
  void run(LowestMode& m, const Eigen::VectorXd* start, bool below_floor) {
    Eigen::VectorXd x(H_.rows());
    if (start != nullptr && start->size() == x.size()) {
      x = *start;
    } else {
      for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = uniform_(rng_);
    }
    project(x);
    double theta_before = 0.0;
    for (int k = 0; k < iterations_; ++k) {
      Eigen::VectorXd y = solver_.solve(Eigen::VectorXd(mass_.cwiseProduct(x)));
      // theta = x'M (H + sM)^-1 M x, the Rayleigh quotient of the iteration's
      // operator (1 / (lambda + s) at an eigenvector), from the solve made.
      const double theta = m_dot(x, y);
      x = std::move(y);
      project(x);
      ++m.iterations;
      if (k > 0 && std::abs(theta - theta_before) < converged_change_ * std::abs(theta)) break;
      if (below_floor && k > 0 && 1.0 / theta - shift_ <= zero_floor_ &&
          std::abs(theta - theta_before) < 1e-2 * std::abs(theta))
        break;
      theta_before = theta;
    }
    m.eigenvalue = x.dot(H_ * x);
    m.ok = std::isfinite(m.eigenvalue);
    m.vector = std::move(x);
  }

  std::vector<Eigen::VectorXd> found;  // unstable modes, M-orthonormal

 private:
  double m_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    return a.dot(mass_.cwiseProduct(b));
  }
  // y M-orthogonal to the modes found, M-normalized.
  void project(Eigen::VectorXd& y) const {
    for (const Eigen::VectorXd& u : found) y -= m_dot(u, y) * u;
    y /= std::sqrt(m_dot(y, y));
  }

  CholeskySolver& solver_;
  const Eigen::SparseMatrix<double>& H_;
  const Eigen::VectorXd& mass_;
  const int iterations_;
  const double shift_;  // s
  const double zero_floor_;
  const double converged_change_;
  std::mt19937 rng_{12345};
  std::uniform_real_distribution<double> uniform_{-1.0, 1.0};
};

}  // namespace

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

  DeflatedInverseIteration iteration(solver, H, mass, iterations, f.shift, zero_floor,
                                     converged_change);
  iteration.run(mode, warm != nullptr && warm->lowest.ok ? &warm->lowest.vector : nullptr, false);
  if (!mode.ok || mode.eigenvalue > zero_floor) {
    estimate.stable = mode;
    return estimate;
  }
  iteration.found.push_back(mode.vector);
  estimate.unstable_modes = 1;
  const Eigen::VectorXd* start =
      warm != nullptr && warm->stable.ok ? &warm->stable.vector : nullptr;
  for (int k = 1; k <= max_unstable; ++k) {
    LowestMode next;
    next.shifted = true;
    next.shift = f.shift;
    iteration.run(next, start, true);
    start = nullptr;
    if (!next.ok) break;
    if (next.eigenvalue > zero_floor) {
      refine_above(next, iteration.found, H, mass);
      estimate.stable = std::move(next);
      break;
    }
    iteration.found.push_back(next.vector);
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
