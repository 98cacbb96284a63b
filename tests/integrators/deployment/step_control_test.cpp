#include "integrators/deployment/step_control.hpp"

#include <doctest/doctest.h>

#include <cstddef>
#include <vector>

namespace xshell::test {

namespace {

// The values of s accepted while every attempt succeeds after `iterations`
// iterations (no jumps).
std::vector<double> accepted_values(StepControl control, long iterations) {
  std::vector<double> values;
  while (!control.done() && values.size() < 100) {
    values.push_back(control.next());
    control.accepted(iterations, false);
  }
  return values;
}

}  // namespace

TEST_CASE("Equal increments land on the grid s = k / steps, after halvings too") {
  CHECK(accepted_values(StepControl(4, 0.0), 1) == std::vector<double>{0.25, 0.5, 0.75, 1.0});
  StepControl control(4, 0.0);
  control.accepted(3, false);  // at 0.25
  CHECK(control.next() == 0.5);
  control.failed();
  CHECK(control.next() == doctest::Approx(0.375));
  control.failed();
  CHECK(control.next() == doctest::Approx(0.3125));
  control.accepted(9, false);
  CHECK(control.next() == doctest::Approx(0.4375));  // doubled back up, still short of 0.5
  control.accepted(9, false);
  CHECK(control.next() == 0.5);  // never carried past the grid point
  control.accepted(1, false);
  CHECK(control.next() == 0.75);  // easy steps do not grow equal increments
  control.accepted(1, false);
  control.accepted(1, false);
  CHECK(control.done());
}

TEST_CASE("Adaptive increments double after easy steps up to the largest, the last ends at 1") {
  const std::vector<double> easy = accepted_values(StepControl(16, 0.25), 2);
  REQUIRE(easy.size() == 6);
  const std::vector<double> expected{0.0625, 0.1875, 0.4375, 0.6875, 0.9375, 1.0};
  for (std::size_t k = 0; k < easy.size(); ++k) CHECK(easy[k] == doctest::Approx(expected[k]));
  // Three iterations neither grow nor shrink the increment.
  CHECK(accepted_values(StepControl(4, 0.5), 3) == std::vector<double>{0.25, 0.5, 0.75, 1.0});
  // A largest increment below 1 / steps is 1 / steps.
  CHECK(accepted_values(StepControl(4, 0.01), 1) == std::vector<double>{0.25, 0.5, 0.75, 1.0});
}

TEST_CASE("A hard step or a jump brings a grown increment back to 1 / steps") {
  StepControl control(10, 0.8);
  control.accepted(1, false);  // 0.1; increment 0.2
  control.accepted(1, false);  // 0.3; increment 0.4
  CHECK(control.next() == doctest::Approx(0.7));
  control.accepted(StepControl::kHardIterations + 1, false);
  CHECK(control.next() == doctest::Approx(0.8));
  control.accepted(1, false);  // grows again: 0.2
  CHECK(control.next() == doctest::Approx(1.0));
  StepControl jumping(10, 0.8);
  jumping.accepted(1, false);  // 0.1; increment 0.2
  jumping.accepted(1, true);   // 0.3, a saddle left: back to 0.1
  CHECK(jumping.next() == doctest::Approx(0.4));
  // A failure halves the grown increment, and a success after it that is
  // neither easy nor hard keeps it.
  StepControl failing(10, 0.8);
  failing.accepted(1, false);
  failing.accepted(1, false);  // 0.3; increment 0.4
  failing.failed();            // 0.2
  CHECK(failing.next() == doctest::Approx(0.5));
  failing.accepted(4, false);
  CHECK(failing.next() == doctest::Approx(0.7));
}

}  // namespace xshell::test
