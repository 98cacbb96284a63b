// Inverse design of a linkage by its segment rest lengths p (one per
// segment, RodLinkage::segment_rest_lengths, docs/model.md section 9.7):
//   J(p) = w_fit F(x_dep) + w_dep E(x_dep) + w_flat E(x_flat) + w_reg R(p),
//   R(p) = 1/2 sum_s ((p_s - p0_s) / p0_s)^2,
// F the fit of chosen vertices to target positions (vertex_targets.hpp), E
// the total energy, x_dep the equilibrium at the deployed average opening
// angle A and x_flat the one at the flat (start) state's average angle,
// each under its average-angle constraint (average_constraint.hpp), p0 the
// start's rest lengths. A target surface moves the targets to the closest
// points of the deployed joints at every evaluation (DesignOptions::retarget):
// the gradient of the squared distance, x - c(x), needs no derivative of c.
//
// Gradient by the adjoint method. At a constrained equilibrium
//   g(x, p) = tau a,  a . x = A,
// so dx/dp solves [H a; a^T 0] [dx/dp; -dtau/dp] = [-G; 0] with
// G = d g / dp (RodLinkage::gradient_rest_length_derivative, free rows),
// and the fit's total derivative is
//   d F / dp = -lambda^T G,  [H a; a^T 0] [lambda; mu] = [dF/dx; 0]
// (one adjoint solve, HeldEquilibrium::adjoint). The energies need none:
//   dE(x*(p), p)/dp = dE/dp + g . dx/dp = dE/dp + tau a . dx/dp = dE/dp
// (RodLinkage::energy_rest_length_derivative), as a . dx/dp = 0.
//
// Loads that are lumped on the rest lengths (gravity, line loads) are
// refused: their derivative is not modelled. Point forces are allowed.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "integrators/design/held_equilibrium.hpp"
#include "integrators/design/vertex_targets.hpp"

namespace xshell {

struct DesignWeights {
  double fit = 1.0;              // w_fit (1 / length^2 x energy, say)
  double deployed_energy = 0.0;  // w_dep
  double flat_energy = 0.0;      // w_flat; 0: the flat equilibrium is not solved at all
  double regularization = 0.0;   // w_reg (R is unit-free)
};

struct DesignOptions {
  double deployed_angle = 0.0;        // A, radians
  std::vector<VertexTarget> targets;  // fitted at the deployed equilibrium
  DesignWeights weights;
  // Each equilibrium's solve; gradient_tolerance sets how exact J and its
  // gradient are (the gradient is that of the exact equilibria).
  NewtonOptions newton;
  int deployment_steps = 10;  // continuation to A at construction
  // When given: sets the targets' positions from the deployed equilibrium
  // before the fit is evaluated (closest points of a target surface).
  std::function<void(const RodLinkage& deployed, std::vector<VertexTarget>& targets)> retarget;
};

enum class DesignStatus {
  Ok,
  InvalidLengths,  // wrong count, or a length not positive and finite
  NotConverged,    // an equilibrium was not found; the previous ones are kept
  AdjointFailed,   // no factorization for the adjoint (an unstable equilibrium); value valid
};
const char* to_string(DesignStatus status);

struct DesignTerms {  // unweighted
  double fit = 0.0, deployed_energy = 0.0, flat_energy = 0.0, regularization = 0.0;
};

struct DesignEvaluation {
  DesignStatus status = DesignStatus::Ok;
  std::string reason;        // when not Ok
  double value = 0.0;        // J (valid for Ok and AdjointFailed)
  Eigen::VectorXd gradient;  // dJ/dp (num_parameters()), empty unless Ok
  DesignTerms terms;
};

class DesignObjective {
 public:
  // `flat`: the problem at its flat (start) state, whose average opening
  // angle is the flat equilibrium's. Deploys a copy to A (deploy(),
  // deployment_steps steps). `flat_held`, when given, is the flat
  // equilibrium's problem instead of `flat` (the same linkage under other
  // supports: held in its plane). Throws ModelError for loads lumped on the
  // rest lengths or a target that is not a vertex (vertex_position_terms),
  // and std::runtime_error when the start's equilibria cannot be found.
  DesignObjective(const LinkageProblem& flat, DesignOptions options,
                  const LinkageProblem* flat_held = nullptr);
  ~DesignObjective();

  int num_parameters() const { return static_cast<int>(start_lengths_.size()); }
  const std::vector<double>& start_lengths() const { return start_lengths_; }
  const DesignOptions& options() const { return options_; }
  void set_weights(const DesignWeights& weights) { options_.weights = weights; }
  // The targets as last evaluated (moved by DesignOptions::retarget).
  const std::vector<VertexTarget>& targets() const { return targets_; }

  // J and dJ/dp at p = lengths: re-solves the equilibria from the last
  // accepted ones (warm start). A failure leaves them as they were and is
  // reported in the status, never thrown, so that a line search can
  // reject the iterate.
  DesignEvaluation evaluate(const std::vector<double>& lengths);

  const LinkageProblem& deployed() const { return deployed_->problem(); }
  // Null when w_flat = 0.
  const LinkageProblem* flat() const { return flat_ ? &flat_->problem() : nullptr; }

 private:
  // Solves every equilibrium at p; false (all back to their accepted states)
  // on the first failure.
  bool solve(const std::vector<double>& lengths, std::string& reason);
  // J's terms and value at the current equilibria.
  void evaluate_terms(const std::vector<double>& lengths, DesignEvaluation& out);
  // dJ/dp; false when the adjoint has no factorization.
  bool gradient(const std::vector<double>& lengths, Eigen::VectorXd& out);

  DesignOptions options_;
  std::vector<double> start_lengths_;
  std::vector<VertexTarget> targets_;
  std::unique_ptr<HeldEquilibrium> deployed_, flat_;
};

}  // namespace xshell
