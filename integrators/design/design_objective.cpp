#include "integrators/design/design_objective.hpp"

#include <cmath>
#include <stdexcept>

#include "integrators/deployment/deployment.hpp"
#include "linkage/model_error.hpp"

namespace xshell {

namespace {

std::unique_ptr<HeldEquilibrium> held_at(const LinkageProblem& problem, double angle,
                                         const NewtonOptions& newton, const char* name) {
  auto held = std::make_unique<HeldEquilibrium>(problem, angle, newton);
  std::string reason;
  if (!held->solve(nullptr, reason))
    throw std::runtime_error(std::string("design: the ") + name +
                             " equilibrium at the start's rest lengths was not found: " + reason);
  held->accept();
  return held;
}

bool valid_lengths(const std::vector<double>& lengths, int count, std::string& reason) {
  if (static_cast<int>(lengths.size()) != count) {
    reason = std::to_string(lengths.size()) + " rest lengths given for " + std::to_string(count) +
             " segments";
    return false;
  }
  for (std::size_t s = 0; s < lengths.size(); ++s)
    if (!std::isfinite(lengths[s]) || lengths[s] <= 0.0) {
      reason = "segment " + std::to_string(s) + " has rest length " + std::to_string(lengths[s]);
      return false;
    }
  return true;
}

// x restricted to the free unknowns of `problem` (LinkageProblem::with_fixed_zero
// goes back).
Eigen::VectorXd free_part(const LinkageProblem& problem, const Eigen::VectorXd& x) {
  Eigen::VectorXd out(problem.num_free());
  for (int i = 0; i < problem.num_free(); ++i) out[i] = x[problem.free_indices()[i]];
  return out;
}

}  // namespace

const char* to_string(DesignStatus status) {
  switch (status) {
    case DesignStatus::Ok:
      return "ok";
    case DesignStatus::InvalidLengths:
      return "invalid rest lengths";
    case DesignStatus::NotConverged:
      return "equilibrium not found";
    case DesignStatus::AdjointFailed:
      return "adjoint solve failed";
  }
  return "unknown";
}

DesignObjective::DesignObjective(const LinkageProblem& flat, DesignOptions options,
                                 const LinkageProblem* flat_held)
    : options_(std::move(options)),
      start_lengths_(flat.linkage().segment_rest_lengths()),
      targets_(options_.targets) {
  if (flat.has_rest_length_loads())
    throw ModelError(
        "design: gravity and line loads are lumped on the rest lengths, and their derivative is "
        "not modelled; inverse design needs a problem without them");
  for (const VertexTarget& t : targets_) vertex_position_terms(flat.linkage(), t.vertex);
  if (options_.weights.flat_energy != 0.0)
    flat_ = held_at(flat_held ? *flat_held : flat, average_opening_angle(flat.linkage()),
                    options_.newton, "flat");
  LinkageProblem deployed = flat;
  DeploymentPlan plan;
  plan.average_angle = options_.deployed_angle;
  plan.steps = options_.deployment_steps;
  DeploymentOptions deployment;
  deployment.newton = options_.newton;
  const DeploymentResult result = deploy(deployed, plan, deployment);
  if (result.status != SolveStatus::Converged)
    throw std::runtime_error("design: the deployment to the deployed angle failed: " +
                             result.reason);
  deployed_ = held_at(deployed, options_.deployed_angle, options_.newton, "deployed");
}

DesignObjective::~DesignObjective() = default;

bool DesignObjective::solve(const std::vector<double>& lengths, std::string& reason) {
  if (!deployed_->solve(&lengths, reason)) return false;
  if (flat_ && !flat_->solve(&lengths, reason)) {
    deployed_->reject();
    return false;
  }
  deployed_->accept();
  if (flat_) flat_->accept();
  return true;
}

void DesignObjective::evaluate_terms(const std::vector<double>& lengths, DesignEvaluation& out) {
  const DesignWeights& w = options_.weights;
  DesignTerms& t = out.terms;
  if (options_.retarget) options_.retarget(deployed().linkage(), targets_);
  t.fit = target_fit(deployed().linkage(), targets_);
  t.deployed_energy = deployed().energy().total();
  t.flat_energy = flat_ ? flat_->problem().energy().total() : 0.0;
  for (std::size_t s = 0; s < lengths.size(); ++s)
    t.regularization += 0.5 * std::pow(lengths[s] / start_lengths_[s] - 1.0, 2);
  out.value = w.fit * t.fit + w.deployed_energy * t.deployed_energy +
              w.flat_energy * t.flat_energy + w.regularization * t.regularization;
}

bool DesignObjective::gradient(const std::vector<double>& lengths, Eigen::VectorXd& out) {
  const DesignWeights& w = options_.weights;
  const RodLinkage& linkage = deployed().linkage();
  out = w.deployed_energy * linkage.energy_rest_length_derivative();
  if (flat_) out += w.flat_energy * flat_->problem().linkage().energy_rest_length_derivative();
  for (std::size_t s = 0; s < lengths.size(); ++s)
    out[s] += w.regularization * (lengths[s] / start_lengths_[s] - 1.0) / start_lengths_[s];
  if (w.fit == 0.0 || targets_.empty()) return true;
  const Eigen::VectorXd f = w.fit * free_part(deployed(), target_fit_gradient(linkage, targets_));
  const Eigen::VectorXd lambda = deployed_->adjoint(f);
  if (lambda.size() == 0) return false;
  out -= linkage.gradient_rest_length_derivative().transpose() * deployed().with_fixed_zero(lambda);
  return true;
}

DesignEvaluation DesignObjective::evaluate(const std::vector<double>& lengths) {
  DesignEvaluation out;
  if (!valid_lengths(lengths, num_parameters(), out.reason)) {
    out.status = DesignStatus::InvalidLengths;
    return out;
  }
  if (!solve(lengths, out.reason)) {
    out.status = DesignStatus::NotConverged;
    return out;
  }
  evaluate_terms(lengths, out);
  if (!gradient(lengths, out.gradient)) {
    out.gradient.resize(0);
    out.status = DesignStatus::AdjointFailed;
    out.reason = "the constrained Hessian at the deployed equilibrium could not be factorized";
  }
  return out;
}

}  // namespace xshell
