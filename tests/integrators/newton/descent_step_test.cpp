// The energy line search's expansion along a path (backtrack_on_energy):
// a full step is doubled only where the quadratic through the start, its
// slope and the full step's energy falls further.

#include "integrators/newton/descent_step.hpp"

#include <doctest/doctest.h>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/toy_objectives.hpp"

namespace xshell {
namespace {

// E = k q^2 / 2 - f q from q = 0 along p = fraction * (f / k) (Newton's
// step times `fraction`), the line given as the path so that the search
// may expand.
DescentStepResult step_on_parabola(double fraction, Eigen::VectorXd& end) {
  const double k = 4.0, f = 2.0;
  test::Quadratic parabola(Eigen::MatrixXd::Constant(1, 1, k), Eigen::VectorXd::Constant(1, f));
  ObjectiveEvaluator evaluator(parabola);
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(1);
  const Eigen::VectorXd p = Eigen::VectorXd::Constant(1, fraction * f / k);
  BacktrackingMerit merit;
  merit.phi0 = 0.0;
  merit.slope = -f * p[0];
  merit.path = [&](double alpha) { return Eigen::VectorXd(q0 + alpha * p); };
  const DescentStepResult out =
      backtrack_on_energy(evaluator, q0, 0.0, p, merit, DescentStepOptions{});
  end = parabola.get();
  return out;
}

TEST_CASE("A full Newton step on a quadratic is not doubled: the one trial") {
  // E(1) - E(0) = slope / 2: the quadratic's minimum is the full step, and
  // doubling lands back at E(0). No trial beyond the full step.
  Eigen::VectorXd end;
  const DescentStepResult step = step_on_parabola(1.0, end);
  REQUIRE(step.accepted);
  CHECK(step.trials == 1);
  CHECK(step.step_fraction == 1.0);
  CHECK(end[0] == doctest::Approx(0.5));
}

TEST_CASE("A step that falls short of the minimum is still doubled along the path") {
  // A quarter of Newton's step: E(1) - E(0) = 7/8 slope, the quadratic's
  // minimum at alpha = 4, reached by doubling twice; alpha = 8 is tried
  // and refused (E back at E(0)).
  Eigen::VectorXd end;
  const DescentStepResult step = step_on_parabola(0.25, end);
  REQUIRE(step.accepted);
  CHECK(step.step_fraction == 4.0);
  CHECK(step.trials == 4);
  CHECK(end[0] == doctest::Approx(0.5));
}

}  // namespace
}  // namespace xshell
