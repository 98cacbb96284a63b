// The objective as the SUNDIALS callbacks see it.
//
// KINSOL and IDA call back with their own iterates; this class moves the
// model there only when needed (set() can be expensive), evaluates the
// gradient, and turns every failure into a return code, because no C++
// exception may unwind through the C libraries:
//   - std::domain_error from set() (an invalid configuration) and NaN/inf
//     values are recoverable (return 1): the solver backtracks or cuts its
//     step. The last failure is recorded so that the driver can report it.
//   - any other exception is unrecoverable (return -1); it is stored and
//     rethrown by the driver once the C library has returned.
#pragma once

#include <Eigen/Core>
#include <exception>
#include <string>

#include "integrators/common/objective.hpp"

namespace xshell {

enum class EvaluationFailure {
  None,
  NonFinite,             // energy, gradient or Hessian held NaN or inf
  InvalidConfiguration,  // set() threw std::domain_error
};

class ObjectiveEvaluator {
 public:
  explicit ObjectiveEvaluator(Objective& objective) : objective_(objective) {}

  Objective& objective() { return objective_; }
  Eigen::Index size() const { return objective_.size(); }

  // Records that the objective's current get() is where it is now (after a
  // rebase or a set() made outside this class). Drops cached values.
  void sync();
  // Moves the objective to q (size()) unless it is there already. Throws
  // what set() throws; afterwards the position is unknown.
  void move_to(const Eigen::Ref<const Eigen::VectorXd>& q);
  // Where the objective is: the last sync() or move, else its get().
  Eigen::VectorXd position() const { return known_ ? position_ : objective_.get(); }
  // The gradient at the current position (cached until the next move).
  const Eigen::VectorXd& gradient();
  // Moves to q (as move_to) and returns the energy there, computed in the
  // same pass as the move when it moves (cached until the next move).
  double energy_at(const Eigen::Ref<const Eigen::VectorXd>& q);

  // Callback helpers: move to q, then copy the gradient into g. Return 0,
  // 1 (recoverable: invalid or non-finite) or -1 (stored exception).
  int gradient_at(const double* q, double* g);
  // Moves to q only. Same return codes.
  int move_to(const double* q);
  // Moves to q and stores the energy there (as energy_at). Same return codes.
  int energy_at(const double* q, double* energy);

  // Failure bookkeeping, reset by clear_failures().
  void record(EvaluationFailure failure, std::string message);
  int fail_with_current_exception();  // for catch (...) blocks: returns 1 or -1
  void clear_failures();
  EvaluationFailure last_failure() const { return last_failure_; }
  const std::string& last_message() const { return last_message_; }
  long failures() const { return failures_; }
  // An exception stored by a callback, to be rethrown once the C library
  // has returned: rethrow_if_fatal() rethrows it (and clears it).
  bool has_fatal() const { return static_cast<bool>(fatal_); }
  void rethrow_if_fatal();

 private:
  // True when the objective is known to be at q.
  bool is_at(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  Objective& objective_;
  Eigen::VectorXd position_;  // where the objective is, when known_
  bool known_ = false;
  Eigen::VectorXd gradient_;
  bool gradient_valid_ = false;
  double energy_ = 0.0;
  bool energy_valid_ = false;

  EvaluationFailure last_failure_ = EvaluationFailure::None;
  std::string last_message_;
  long failures_ = 0;
  std::exception_ptr fatal_;
};

// max_i |w_i g_i|, or NaN when g or w holds NaN (so that the result never
// hides a non-finite gradient). 0 for empty vectors.
double weighted_max_norm(const Eigen::VectorXd& weights, const Eigen::VectorXd& g);

}  // namespace xshell
