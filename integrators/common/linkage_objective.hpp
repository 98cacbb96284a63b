// The linkage statics problem seen as a solver Objective: free unknowns,
// total energy (elastic plus load potential), its gradient and Hessian, the
// dimensionless convergence weights, masses and the rebase (source-frame
// update and joint fold) that the solvers call between iterations.
#pragma once

#include <optional>

#include "integrators/common/objective.hpp"
#include "linkage/edge_rotation_path.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

class LinkageObjective : public Objective {
 public:
  explicit LinkageObjective(LinkageProblem& problem) : problem_(problem) {}

  Eigen::Index size() const override { return problem_.num_free(); }
  Eigen::VectorXd get() const override { return problem_.free_dofs(); }
  void set(const Eigen::VectorXd& q) override { problem_.set_free_dofs(q); }
  double energy() const override { return problem_.energy().total(); }
  double set_and_energy(const Eigen::VectorXd& q) override {
    return problem_.set_free_dofs_and_energy(q);
  }
  Eigen::VectorXd gradient() const override { return problem_.free_gradient(); }
  const Eigen::SparseMatrix<double>& hessian() override { return problem_.free_hessian(); }
  Eigen::VectorXd gradient_weights() const override { return problem_.gradient_weights(); }
  Eigen::VectorXd mass() const override { return problem_.free_mass(); }
  void rebase(Eigen::VectorXd* velocity) override { problem_.rebase(velocity); }
  // The joints follow their turned chords on unshifted Newton steps only:
  // on shifted ones they led the iterates into indefinite regions
  // (docs/model.md section 9.8).
  bool begin_path(const Eigen::VectorXd& p, bool newton_step) override {
    if (!path_) path_.emplace(problem_);
    path_->start(problem_, p, newton_step);
    return true;
  }
  Eigen::VectorXd path_point(double alpha) override { return path_->point(problem_, alpha); }
  // The stretching's axial forces (LinkageProblem::use_mixed_hessian).
  void use_mixed_hessian(const Eigen::VectorXd& p) override { problem_.use_mixed_hessian(p); }
  void use_exact_hessian() override { problem_.use_exact_hessian(); }

  LinkageProblem& problem() { return problem_; }

 private:
  LinkageProblem& problem_;
  std::optional<EdgeRotationPath> path_;  // made at the first begin_path
};

}  // namespace xshell
