// A toy Objective assembled from local energy terms ("stencils"), for the
// integrator tests.
//
// The configuration is a vector x of dofs; some are pinned, the others are
// the free unknowns q = x[free] in increasing dof order. Each term reads a
// few dofs and returns a Dual (value, local gradient, local Hessian); the
// global gradient and Hessian are assembled here, in one place, with the
// pattern fixed at construction (it includes the whole diagonal).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <string>
#include <vector>

#include "integrators/common/objective.hpp"
#include "integrators/dual_vectors.hpp"

namespace xshell::test {

struct LocalEnergy {
  double value = 0.0;
  Eigen::VectorXd gradient;  // local size
  Eigen::MatrixXd hessian;   // local size^2 (fixed-size stencil, tiny)
};

struct Term {
  std::vector<int> dofs;
  std::function<LocalEnergy(const Eigen::VectorXd& local)> evaluate;
};

// A term of N dofs from a generic energy formula f(std::array<Dual<N>, N>).
template <int N, class Formula>
Term make_term(const std::array<int, N>& dofs, Formula formula) {
  Term term;
  term.dofs.assign(dofs.begin(), dofs.end());
  term.evaluate = [formula](const Eigen::VectorXd& local) {
    std::array<Dual<N>, N> x;
    for (int i = 0; i < N; ++i) x[static_cast<size_t>(i)] = Dual<N>::variable(i, local[i]);
    const Dual<N> e = formula(x);
    return LocalEnergy{e.v, e.g, e.h};
  };
  return term;
}

class StencilObjective : public Objective {
 public:
  // x0: the full configuration (pinned dofs keep their value); pinned: dofs
  // that are not unknowns; terms: the energy. mass: lumped mass per dof
  // (full size; ones if empty).
  StencilObjective(Eigen::VectorXd x0, const std::vector<int>& pinned, std::vector<Term> terms,
                   Eigen::VectorXd mass = {});

  Eigen::Index size() const override { return static_cast<Eigen::Index>(free_.size()); }
  Eigen::VectorXd get() const override;
  void set(const Eigen::VectorXd& q) override;
  double energy() const override;
  Eigen::VectorXd gradient() const override;
  const Eigen::SparseMatrix<double>& hessian() override;
  Eigen::VectorXd gradient_weights() const override;
  Eigen::VectorXd mass() const override;

  const Eigen::VectorXd& configuration() const { return x_; }
  long evaluations() const { return evaluations_; }  // term sweeps done

 private:
  Eigen::VectorXd local_values(const Term& term) const;

  Eigen::VectorXd x_;
  std::vector<int> free_;        // unknown i -> dof
  std::vector<int> unknown_of_;  // dof -> unknown, or -1 if pinned
  std::vector<Term> terms_;
  Eigen::VectorXd mass_;
  Eigen::SparseMatrix<double> hessian_;
  // For every term, the value index in hessian_ of each local (a, b) pair
  // (a-major), or -1 when a or b is pinned.
  std::vector<std::vector<int>> slots_;
  mutable long evaluations_ = 0;
};

// Finite-difference checks of an objective's derivatives at its current
// configuration: max relative errors of the gradient against central
// differences of energy(), and of the Hessian against central differences
// of gradient(). Restores the configuration.
struct DerivativeErrors {
  double gradient = 0.0;
  double hessian = 0.0;
  int checked_entries = 0;  // gradient + Hessian entries compared
};
DerivativeErrors check_derivatives(Objective& objective, double step = 1e-6);

}  // namespace xshell::test
