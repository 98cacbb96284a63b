// An equilibrium of a linkage held at an average opening angle A
// (average_constraint.hpp), followed as the segment rest lengths change:
// each solve starts from the last accepted equilibrium (warm start) and,
// when it fails, returns to it. The adjoint solves reuse the constrained
// Newton solver's CHOLMOD symbolic analyses (inverse design,
// docs/model.md section 9.7).
#pragma once

#include <string>
#include <vector>

#include "integrators/common/linkage_objective.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/constrained_newton.hpp"

namespace xshell {

class HeldEquilibrium {
 public:
  // A copy of `problem`, held at `angle` (radians) from its current state
  // (the accepted one), which should be near an equilibrium at that angle.
  HeldEquilibrium(const LinkageProblem& problem, double angle, const NewtonOptions& newton);
  HeldEquilibrium(const HeldEquilibrium&) = delete;
  HeldEquilibrium& operator=(const HeldEquilibrium&) = delete;

  // Sets the segment rest lengths (null: keeps them) and solves from the
  // current state. On failure the problem returns to the accepted state
  // (lengths included) and `reason` says why. Throws ModelError as
  // LinkageProblem::set_segment_rest_lengths.
  bool solve(const std::vector<double>* lengths, std::string& reason);
  // Makes the current state the accepted one, or returns to the accepted
  // one (when another equilibrium of the same design failed).
  void accept() { accepted_ = problem_; }
  void reject() { problem_ = accepted_; }

  const LinkageProblem& problem() const { return problem_; }
  double angle() const { return angle_; }
  // The last solve's result.
  const ConstrainedNewtonResult& result() const { return result_; }
  // ConstrainedNewtonSolver::adjoint at the current state (f: num_free()).
  Eigen::VectorXd adjoint(const Eigen::VectorXd& f) { return solver_.adjoint(f); }

 private:
  LinkageProblem problem_;
  LinkageObjective objective_;
  AverageConstraint constraint_;
  ConstrainedNewtonSolver solver_;
  double angle_;
  LinkageProblem accepted_;
  ConstrainedNewtonResult result_;
};

}  // namespace xshell
