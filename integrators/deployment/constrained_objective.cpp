#include "integrators/deployment/constrained_objective.hpp"

#include <stdexcept>

namespace xshell {

ConstrainedObjective::ConstrainedObjective(Objective& inner, const AverageConstraint& constraint)
    : inner_(inner), constraint_(constraint) {
  if (inner.size() != constraint.size())
    throw std::invalid_argument("constrained objective: the constraint does not fit the objective");
  const Eigen::VectorXd q = inner.get();
  offset_ = Eigen::VectorXd::Zero(q.size());
  for (int i : constraint.members()) offset_[i] = q[i];
}

Eigen::VectorXd ConstrainedObjective::get() const {
  return constraint_.coordinates(inner_.get() - offset_);
}

void ConstrainedObjective::set(const Eigen::VectorXd& z) {
  inner_.set(offset_ + constraint_.expand(z));
}

double ConstrainedObjective::set_and_energy(const Eigen::VectorXd& z) {
  return inner_.set_and_energy(offset_ + constraint_.expand(z));
}

const Eigen::SparseMatrix<double>& ConstrainedObjective::hessian() {
  constraint_.reduce(inner_.hessian(), hessian_);
  return hessian_;
}

Eigen::VectorXd ConstrainedObjective::gradient_weights() const {
  return constraint_.reduce_weights(inner_.gradient_weights());
}

void ConstrainedObjective::rebase(Eigen::VectorXd* velocity) {
  if (!velocity) {
    inner_.rebase();
    return;
  }
  Eigen::VectorXd v = constraint_.expand(*velocity);
  inner_.rebase(&v);
  *velocity = constraint_.coordinates(v);
}

}  // namespace xshell
