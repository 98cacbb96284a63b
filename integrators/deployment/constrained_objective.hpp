// An objective restricted to an average constraint by a change of
// variables (average_constraint.hpp): q = c + B z, with c the averaged
// unknowns' values at construction (0 elsewhere), so that every z keeps
// the constraint's value of the starting point exactly. The solvers then
// see an unconstrained problem in z (size n - 1): this is how damped
// dynamics (IDA) is deployed without an algebraic (index-3) position
// constraint. Gradient B^T g, Hessian B^T H B (sparse, fixed pattern),
// lumped mass diag(B^T M B), gradient weights of the corresponding q entries.
//
// The inner objective's rebase must leave the averaged unknowns (the
// opening angles) unchanged, as the linkage's does: then c stays valid and
// the velocity is carried through B.
#pragma once

#include "integrators/common/objective.hpp"
#include "integrators/deployment/average_constraint.hpp"

namespace xshell {

class ConstrainedObjective : public Objective {
 public:
  // `inner` is at the starting point; both must outlive this object.
  ConstrainedObjective(Objective& inner, const AverageConstraint& constraint);

  Eigen::Index size() const override { return constraint_.reduced_size(); }
  Eigen::VectorXd get() const override;
  void set(const Eigen::VectorXd& z) override;
  double energy() const override { return inner_.energy(); }
  double set_and_energy(const Eigen::VectorXd& z) override;
  Eigen::VectorXd gradient() const override { return constraint_.restrict(inner_.gradient()); }
  const Eigen::SparseMatrix<double>& hessian() override;
  Eigen::VectorXd gradient_weights() const override;
  Eigen::VectorXd mass() const override { return constraint_.reduce_diagonal(inner_.mass()); }
  void rebase(Eigen::VectorXd* velocity = nullptr) override;

  // The constraint's multiplier (torque) at the current configuration.
  double multiplier() const { return constraint_.multiplier(inner_.gradient()); }

 private:
  Objective& inner_;
  const AverageConstraint& constraint_;
  Eigen::VectorXd offset_;  // c
  Eigen::SparseMatrix<double> hessian_;
};

}  // namespace xshell
