// The longest step IDA may try while the Jacobian of its implicit steps,
// K = H + c_j C + (c_j^2 + a c_j) M (second order) or H + c_j C (first
// order), is not positive definite for long ones.
//
// Near a saddle (H indefinite), K is positive definite only for c_j above
// some c_j*, i.e. for steps shorter than about 1 / c_j*. IDA does not know
// this: after a failed factorization it quarters the step, then lets the
// error test grow it again, up to eta_max per step, into the same failure.
// The largest design (1,371 joints, from flat) had such a failure in 76
// of its 92 steps and made 159 factorizations (42 with the cap, in 67
// steps). The cap holds the step below the last
// failure (fraction / c_j: a step of backward Euler, whose c_j is 1 / h,
// or of BDF2, whose c_j is 1.5 / h, has c_j above the failed one) for
// `wait` accepted steps, then lifts it, since the Hessian changes along
// the motion (a linkage that has buckled is stable again). A failure soon
// after a lift doubles the wait (up to max_wait); a lift that holds resets
// it.
#pragma once

#include <limits>

namespace xshell {

class DefiniteStepCap {
 public:
  struct Options {
    double fraction = 0.8;
    int wait = 4;
    int max_wait = 64;
  };

  DefiniteStepCap() = default;
  explicit DefiniteStepCap(const Options& options) : options_(options) {}

  // A factorization failed for c_j = cj > 0. Returns the new cap.
  double on_failure(double cj);
  // An accepted step. Returns true when the cap was lifted.
  bool on_step();

  // Longest step allowed; infinity when none.
  double cap() const { return cap_; }
  bool active() const { return cap_ < std::numeric_limits<double>::infinity(); }
  int wait() const { return wait_; }

 private:
  Options options_;
  double cap_ = std::numeric_limits<double>::infinity();
  int wait_ = options_.wait;
  int since_failure_ = 0;  // accepted steps under the current cap
  int since_lift_ = -1;    // accepted steps since the last lift (-1: none pending)
};

}  // namespace xshell
