#include "integrators/common/objective_evaluator.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace xshell {

void ObjectiveEvaluator::sync() {
  position_ = objective_.get();
  known_ = true;
  gradient_valid_ = energy_valid_ = false;
}

bool ObjectiveEvaluator::is_at(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return known_ && position_.size() == q.size() && position_ == q;
}

void ObjectiveEvaluator::move_to(const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (is_at(q)) return;
  known_ = false;
  gradient_valid_ = energy_valid_ = false;
  objective_.set(q);
  position_ = q;
  known_ = true;
}

double ObjectiveEvaluator::energy_at(const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (is_at(q)) {
    if (!energy_valid_) energy_ = objective_.energy();
  } else {
    known_ = false;
    gradient_valid_ = energy_valid_ = false;
    energy_ = objective_.set_and_energy(q);
    position_ = q;
    known_ = true;
  }
  energy_valid_ = true;
  return energy_;
}

const Eigen::VectorXd& ObjectiveEvaluator::gradient() {
  if (!gradient_valid_) {
    gradient_ = objective_.gradient();
    gradient_valid_ = true;
  }
  return gradient_;
}

int ObjectiveEvaluator::move_to(const double* q) {
  try {
    move_to(Eigen::Map<const Eigen::VectorXd>(q, size()));
    return 0;
  } catch (...) {
    return fail_with_current_exception();
  }
}

int ObjectiveEvaluator::energy_at(const double* q, double* energy) {
  try {
    *energy = energy_at(Eigen::Map<const Eigen::VectorXd>(q, size()));
    return 0;
  } catch (...) {
    return fail_with_current_exception();
  }
}

int ObjectiveEvaluator::gradient_at(const double* q, double* g) {
  try {
    move_to(Eigen::Map<const Eigen::VectorXd>(q, size()));
    const Eigen::VectorXd& gradient = this->gradient();
    if (!gradient.allFinite()) {
      record(EvaluationFailure::NonFinite, "the gradient is not finite");
      return 1;
    }
    Eigen::Map<Eigen::VectorXd>(g, size()) = gradient;
    return 0;
  } catch (...) {
    return fail_with_current_exception();
  }
}

void ObjectiveEvaluator::record(EvaluationFailure failure, std::string message) {
  last_failure_ = failure;
  last_message_ = std::move(message);
  ++failures_;
}

int ObjectiveEvaluator::fail_with_current_exception() {
  try {
    throw;
  } catch (const std::domain_error& e) {
    record(EvaluationFailure::InvalidConfiguration, e.what());
    return 1;
  } catch (...) {
    if (!fatal_) fatal_ = std::current_exception();
    return -1;
  }
}

void ObjectiveEvaluator::clear_failures() {
  last_failure_ = EvaluationFailure::None;
  last_message_.clear();
}

void ObjectiveEvaluator::rethrow_if_fatal() {
  if (fatal_) std::rethrow_exception(std::exchange(fatal_, nullptr));
}

double weighted_max_norm(const Eigen::VectorXd& weights, const Eigen::VectorXd& g) {
  if (g.size() == 0) return 0.0;
  if (!g.allFinite() || !weights.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  return (weights.array() * g.array()).abs().maxCoeff();
}

}  // namespace xshell
