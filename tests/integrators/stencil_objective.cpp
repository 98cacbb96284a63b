#include "stencil_objective.hpp"

#include <algorithm>
#include <stdexcept>

namespace xshell::test {

StencilObjective::StencilObjective(Eigen::VectorXd x0, const std::vector<int>& pinned,
                                   std::vector<Term> terms, Eigen::VectorXd mass)
    : x_(std::move(x0)), terms_(std::move(terms)) {
  const int dofs = static_cast<int>(x_.size());
  unknown_of_.assign(static_cast<size_t>(dofs), 0);
  for (int d : pinned) unknown_of_.at(static_cast<size_t>(d)) = -1;
  for (int d = 0; d < dofs; ++d) {
    if (unknown_of_[static_cast<size_t>(d)] < 0) continue;
    unknown_of_[static_cast<size_t>(d)] = static_cast<int>(free_.size());
    free_.push_back(d);
  }
  mass_ = mass.size() == 0 ? Eigen::VectorXd::Ones(dofs) : std::move(mass);

  const int n = static_cast<int>(free_.size());
  std::vector<Eigen::Triplet<double>> pattern;
  for (int i = 0; i < n; ++i) pattern.emplace_back(i, i, 0.0);
  for (const Term& term : terms_)
    for (int a : term.dofs)
      for (int b : term.dofs) {
        const int i = unknown_of_.at(static_cast<size_t>(a));
        const int j = unknown_of_.at(static_cast<size_t>(b));
        if (i >= 0 && j >= 0) pattern.emplace_back(i, j, 0.0);
      }
  hessian_.resize(n, n);
  hessian_.setFromTriplets(pattern.begin(), pattern.end());
  hessian_.makeCompressed();

  for (const Term& term : terms_) {
    std::vector<int> slots;
    for (int a : term.dofs)
      for (int b : term.dofs) {
        const int i = unknown_of_[static_cast<size_t>(a)];
        const int j = unknown_of_[static_cast<size_t>(b)];
        if (i < 0 || j < 0) {
          slots.push_back(-1);
          continue;
        }
        const int* begin = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[j];
        const int* end = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[j + 1];
        slots.push_back(
            static_cast<int>(std::lower_bound(begin, end, i) - hessian_.innerIndexPtr()));
      }
    slots_.push_back(std::move(slots));
  }
}

Eigen::VectorXd StencilObjective::get() const {
  Eigen::VectorXd q(size());
  for (size_t i = 0; i < free_.size(); ++i) q[static_cast<Eigen::Index>(i)] = x_[free_[i]];
  return q;
}

void StencilObjective::set(const Eigen::VectorXd& q) {
  if (q.size() != size()) throw std::invalid_argument("StencilObjective::set: wrong size");
  for (size_t i = 0; i < free_.size(); ++i) x_[free_[i]] = q[static_cast<Eigen::Index>(i)];
}

Eigen::VectorXd StencilObjective::local_values(const Term& term) const {
  Eigen::VectorXd local(static_cast<Eigen::Index>(term.dofs.size()));
  for (size_t a = 0; a < term.dofs.size(); ++a)
    local[static_cast<Eigen::Index>(a)] = x_[term.dofs[a]];
  return local;
}

double StencilObjective::energy() const {
  ++evaluations_;
  double e = 0.0;
  for (const Term& term : terms_) e += term.evaluate(local_values(term)).value;
  return e;
}

Eigen::VectorXd StencilObjective::gradient() const {
  ++evaluations_;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(size());
  for (const Term& term : terms_) {
    const LocalEnergy local = term.evaluate(local_values(term));
    for (size_t a = 0; a < term.dofs.size(); ++a) {
      const int i = unknown_of_[static_cast<size_t>(term.dofs[a])];
      if (i >= 0) g[i] += local.gradient[static_cast<Eigen::Index>(a)];
    }
  }
  return g;
}

const Eigen::SparseMatrix<double>& StencilObjective::hessian() {
  ++evaluations_;
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros(), 0.0);
  for (size_t t = 0; t < terms_.size(); ++t) {
    const LocalEnergy local = terms_[t].evaluate(local_values(terms_[t]));
    const Eigen::Index m = static_cast<Eigen::Index>(terms_[t].dofs.size());
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index b = 0; b < m; ++b) {
        const int slot = slots_[t][static_cast<size_t>(a * m + b)];
        if (slot >= 0) hessian_.valuePtr()[slot] += local.hessian(a, b);
      }
  }
  return hessian_;
}

Eigen::VectorXd StencilObjective::gradient_weights() const { return Eigen::VectorXd::Ones(size()); }

Eigen::VectorXd StencilObjective::mass() const {
  Eigen::VectorXd m(size());
  for (size_t i = 0; i < free_.size(); ++i) m[static_cast<Eigen::Index>(i)] = mass_[free_[i]];
  return m;
}

DerivativeErrors check_derivatives(Objective& objective, double step) {
  DerivativeErrors errors;
  const Eigen::VectorXd q0 = objective.get();
  const Eigen::VectorXd g0 = objective.gradient();
  const Eigen::SparseMatrix<double> H0 = objective.hessian();
  const Eigen::Index n = q0.size();
  const double g_scale = std::max(g0.lpNorm<Eigen::Infinity>(), 1.0);
  const double h_scale = std::max(H0.coeffs().abs().maxCoeff(), 1.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::VectorXd q = q0;
    q[i] = q0[i] + step;
    objective.set(q);
    const double e_plus = objective.energy();
    const Eigen::VectorXd g_plus = objective.gradient();
    q[i] = q0[i] - step;
    objective.set(q);
    const double e_minus = objective.energy();
    const Eigen::VectorXd g_minus = objective.gradient();
    const double g_fd = (e_plus - e_minus) / (2.0 * step);
    errors.gradient = std::max(errors.gradient, std::abs(g_fd - g0[i]) / g_scale);
    const Eigen::VectorXd column = (g_plus - g_minus) / (2.0 * step);
    errors.hessian = std::max(
        errors.hessian, (column - Eigen::VectorXd(H0.col(i))).lpNorm<Eigen::Infinity>() / h_scale);
    errors.checked_entries += 1 + static_cast<int>(n);
  }
  objective.set(q0);
  return errors;
}

}  // namespace xshell::test
