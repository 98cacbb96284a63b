#include "integrators/design/held_equilibrium.hpp"

#include <stdexcept>

namespace xshell {

HeldEquilibrium::HeldEquilibrium(const LinkageProblem& problem, double angle,
                                 const NewtonOptions& newton)
    : problem_(problem),
      objective_(problem_),
      constraint_(average_opening_angle_constraint(problem_)),
      solver_(objective_, constraint_, newton),
      angle_(angle),
      accepted_(problem) {}

bool HeldEquilibrium::solve(const std::vector<double>* lengths, std::string& reason) {
  if (lengths) problem_.set_segment_rest_lengths(*lengths);
  try {
    // Start on the constraint: the accepted state meets it already unless
    // it was made at another angle.
    Eigen::VectorXd q = problem_.free_dofs();
    constraint_.project(q, angle_);
    problem_.set_free_dofs(q);
    result_ = solver_.solve(angle_);
    if (result_.status == SolveStatus::Converged) return true;
    reason = result_.reason.empty() ? std::string(to_string(result_.status)) : result_.reason;
  } catch (const std::domain_error& e) {
    reason = e.what();
  }
  reject();
  return false;
}

}  // namespace xshell
