#include "integrators/dynamics/ida_step_cap.hpp"

#include <doctest/doctest.h>

#include <limits>

namespace xshell::test {

namespace {

// Accepted steps until the cap is lifted (on_step returns true), at most
// `limit`.
int steps_until_lift(DefiniteStepCap& cap, int limit = 1000) {
  for (int k = 1; k <= limit; ++k)
    if (cap.on_step()) return k;
  return -1;
}

}  // namespace

TEST_CASE("the step cap holds steps below a failed c_j, then lifts") {
  DefiniteStepCap::Options o;
  o.fraction = 0.8;
  o.wait = 4;
  o.max_wait = 16;
  DefiniteStepCap cap(o);
  CHECK_FALSE(cap.active());
  CHECK(cap.on_step() == false);  // nothing to lift

  // Backward Euler's c_j is 1 / h: the failed step was 0.5 long.
  CHECK(cap.on_failure(2.0) == doctest::Approx(0.4));
  CHECK(cap.active());
  // A second failure under the cap lowers it; a failure at a longer step
  // (smaller c_j) does not raise it.
  CHECK(cap.on_failure(4.0) == doctest::Approx(0.2));
  CHECK(cap.on_failure(1.0) == doctest::Approx(0.2));
  // Lifted after `wait` accepted steps.
  CHECK(steps_until_lift(cap) == 4);
  CHECK_FALSE(cap.active());
  CHECK(cap.cap() == std::numeric_limits<double>::infinity());
}

TEST_CASE("the step cap waits longer after each failure soon after a lift, up to max_wait") {
  DefiniteStepCap::Options o;
  o.wait = 4;
  o.max_wait = 16;
  DefiniteStepCap cap(o);
  cap.on_failure(1.0);
  CHECK(steps_until_lift(cap) == 4);
  // The saddle is still there: the step fails again right after the lift.
  cap.on_failure(1.0);
  CHECK(cap.wait() == 8);
  CHECK(steps_until_lift(cap) == 8);
  cap.on_step();
  cap.on_failure(1.0);
  CHECK(cap.wait() == 16);
  CHECK(steps_until_lift(cap) == 16);
  cap.on_failure(1.0);
  CHECK(cap.wait() == 16);  // max_wait
  CHECK(steps_until_lift(cap) == 16);
  // A lift that holds for `wait` steps: the next failure waits the least.
  for (int k = 0; k < 16; ++k) cap.on_step();
  cap.on_failure(1.0);
  CHECK(cap.wait() == 4);
  CHECK(steps_until_lift(cap) == 4);
}

TEST_CASE("the step cap ignores a non-positive c_j") {
  DefiniteStepCap cap;
  cap.on_failure(0.0);
  cap.on_failure(-1.0);
  CHECK_FALSE(cap.active());
}

}  // namespace xshell::test
