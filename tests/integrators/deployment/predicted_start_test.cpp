#include "integrators/deployment/predicted_start.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "integrators/deployment/deployment_fixtures.hpp"
#include "linkage/joint.hpp"

namespace xshell::test {

namespace {

// The dome as drawn (stress-free: energy 0) and a random disturbance of it.
struct Starts {
  LinkageProblem problem = dome_problem(3);
  Eigen::VectorXd drawn = problem.free_dofs();
  Eigen::VectorXd disturbed = drawn + 1e-3 * Eigen::VectorXd::Random(drawn.size());
};

// A free unknown of the first joint with free parameters: its terminal
// edge length a (positive in every valid configuration).
int free_edge_length(const LinkageProblem& problem) {
  for (int j = 0; j < problem.linkage().num_joints(); ++j) {
    const int i = problem.free_position(problem.linkage().joint_dof_offset(j) + kLengthA);
    if (i >= 0) return i;
  }
  return -1;
}

}  // namespace

TEST_CASE("The start of lower energy is chosen, whichever comes first, and the problem is there") {
  Starts s;
  for (const bool drawn_first : {true, false}) {
    CAPTURE(drawn_first);
    const std::vector<Eigen::VectorXd> candidates =
        drawn_first ? std::vector{s.drawn, s.disturbed} : std::vector{s.disturbed, s.drawn};
    const PredictedStart start = lowest_energy_start(s.problem, candidates);
    CHECK(start.index == (drawn_first ? 0 : 1));
    CHECK(s.problem.free_dofs() == s.drawn);
    CHECK(start.energy == s.problem.energy().total());
    CHECK(start.energy < 1e-12 * s.problem.energy().total() + 1e-12);
  }
  s.problem.set_free_dofs(s.disturbed);
  const double disturbed_energy = s.problem.energy().total();
  CHECK(disturbed_energy > 0.0);
  // Equal energies: the earlier one.
  CHECK(lowest_energy_start(s.problem, {s.disturbed, s.disturbed}).index == 0);
  CHECK(lowest_energy_start(s.problem, {s.disturbed}).energy == disturbed_energy);
}

TEST_CASE("A start the problem rejects is skipped, and with none valid the index is -1") {
  Starts s;
  const int length = free_edge_length(s.problem);
  REQUIRE(length >= 0);
  Eigen::VectorXd rejected = s.drawn;
  rejected[length] = -rejected[length];  // a terminal edge of negative length
  const PredictedStart start = lowest_energy_start(s.problem, {rejected, s.disturbed});
  CHECK(start.index == 1);
  CHECK(s.problem.free_dofs() == s.disturbed);
  CHECK(lowest_energy_start(s.problem, {rejected}).index == -1);
  CHECK(lowest_energy_start(s.problem, {}).index == -1);
}

TEST_CASE("A start of non-finite energy is chosen only when no other is valid") {
  Starts s;
  // A rod's interior unknown (not a joint's): accepted, with a NaN energy.
  Eigen::VectorXd nan_energy = s.drawn;
  int interior = -1;
  for (int i = 0; i < nan_energy.size() && interior < 0; ++i) {
    s.problem.set_free_dofs(s.drawn);
    Eigen::VectorXd q = s.drawn;
    q[i] = std::numeric_limits<double>::quiet_NaN();
    try {
      s.problem.set_free_dofs(q);
      interior = i;
    } catch (const std::domain_error&) {
    }
  }
  REQUIRE(interior >= 0);
  nan_energy[interior] = std::numeric_limits<double>::quiet_NaN();
  CHECK(lowest_energy_start(s.problem, {nan_energy, s.disturbed}).index == 1);
  const PredictedStart only = lowest_energy_start(s.problem, {nan_energy});
  CHECK(only.index == 0);
  CHECK_FALSE(std::isfinite(only.energy));
}

}  // namespace xshell::test
