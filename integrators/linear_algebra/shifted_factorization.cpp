#include "integrators/linear_algebra/shifted_factorization.hpp"

#include <algorithm>
#include <cmath>

namespace xshell {

ShiftedFactorization factorize_with_shift(CholeskySolver& solver,
                                          const Eigen::SparseMatrix<double>& H,
                                          const Eigen::VectorXd& mass, const ShiftOptions& options,
                                          double first_tau) {
  ShiftedFactorization result;
  result.status = solver.factorize(H);
  result.factorizations = 1;
  if (result.status != FactorizationStatus::NotPositiveDefinite) return result;

  result.shifted = true;
  const double mass_norm = mass.norm();
  const double scale = mass_norm > 0.0 ? H.norm() / mass_norm : 0.0;
  if (!(scale > 0.0) || !std::isfinite(scale)) return result;  // H == 0 cannot be shifted usefully
  double tau = first_tau > 0.0 ? std::max(options.smallest_tau, first_tau) : options.initial_tau;
  for (int attempt = 0; attempt < options.max_attempts; ++attempt, tau *= options.growth) {
    const Eigen::VectorXd shift = (tau * scale) * mass;
    result.status = solver.factorize(H, &shift);
    ++result.factorizations;
    if (result.status != FactorizationStatus::NotPositiveDefinite) {
      result.tau = tau;
      result.shift = tau * scale;
      return result;
    }
  }
  return result;
}

bool is_positive_definite(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H) {
  return solver.factorize(H) == FactorizationStatus::PositiveDefinite;
}

}  // namespace xshell
