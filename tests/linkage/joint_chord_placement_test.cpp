// Where the edge-turning path puts the joints (joint_chord_placement.hpp,
// docs/model.md section 9.8): a four-bar loop shearing about two held
// joints keeps its sides' lengths, where the straight step stretches them;
// a held joint and a free rod end stay where the straight step puts them.
#include "linkage/joint_chord_placement.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "linkage/statics_problem.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {

// The unit square A, B, C, D, its four sides one rod each (four valence-2
// joints), A and B held in position.
LinkageProblem square_loop() {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  g.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Position}}, {1, {SupportDof::Position}}};
  return LinkageProblem(RodLinkage(g, test_options(RestShape::Input, 4)), setup);
}

// The free unknown of coordinate c of the joint at `vertex` (-1: held).
int joint_unknown(const LinkageProblem& problem, int vertex, int c) {
  const RodLinkage& linkage = problem.linkage();
  const int j = linkage.topology().joint_of_vertex[vertex];
  return problem.free_position(linkage.joint_dof_offset(j) + c);
}

Eigen::Vector3d joint_at(const LinkageProblem& problem, const Eigen::VectorXd& q, int vertex) {
  Eigen::Vector3d x;
  for (int c = 0; c < 3; ++c) x[c] = q[joint_unknown(problem, vertex, c)];
  return x;
}

}  // namespace

TEST_CASE("Joint placement: a shearing four-bar loop keeps its sides' lengths") {
  LinkageProblem problem = square_loop();
  REQUIRE(joint_unknown(problem, 0, 0) < 0);
  REQUIRE(joint_unknown(problem, 2, 0) >= 0);
  JointChordPlacement placement(problem);
  REQUIRE(placement.active());
  placement.start(problem);
  // The linearized shear by phi: C and D move by phi z x (0, 1, 0).
  const double phi = 0.4;
  const Eigen::VectorXd q0 = problem.free_dofs();
  Eigen::VectorXd p = Eigen::VectorXd::Zero(q0.size());
  for (int vertex : {2, 3}) p[joint_unknown(problem, vertex, 0)] = -phi;
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0);
  int checked = 0;
  for (double alpha : {0.25, 1.0, 2.0}) {
    CAPTURE(alpha);
    Eigen::VectorXd q = q0 + alpha * p;
    const double straight_side = (joint_at(problem, q, 3) - a).norm();
    CHECK(straight_side == doctest::Approx(std::hypot(1.0, alpha * phi)).epsilon(1e-12));
    const Eigen::Vector3d straight_d = joint_at(problem, q, 3);
    placement.place(q);
    const Eigen::Vector3d c = joint_at(problem, q, 2), d = joint_at(problem, q, 3);
    const Eigen::Vector3d side(-std::sin(alpha * phi), std::cos(alpha * phi), 0.0);
    // Exact but for the pull towards the straight step, of relative weight
    // kStraightPull.
    const double pull = JointChordPlacement::kStraightPull * (straight_d - (a + side)).norm();
    CHECK((d - (a + side)).norm() < 2.0 * pull);
    CHECK((c - (b + side)).norm() < 2.0 * pull);
    CHECK((c - d).norm() == doctest::Approx(1.0).epsilon(1e-9));
    ++checked;
  }
  CHECK(checked == 3);
}

TEST_CASE("Joint placement: the fit is the straight step to second order") {
  LinkageProblem problem = square_loop();
  JointChordPlacement placement(problem);
  placement.start(problem);
  const Eigen::VectorXd q0 = problem.free_dofs();
  Eigen::VectorXd p = Eigen::VectorXd::Zero(q0.size());
  // A step that turns and stretches the sides, with the opening angles' and
  // frames' unknowns left alone.
  const double steps[2][3] = {{-0.3, 0.1, 0.2}, {0.2, -0.05, -0.1}};
  for (int k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) p[joint_unknown(problem, 2 + k, c)] = steps[k][c];
  double previous = 0.0;
  int halvings = 0;
  for (double alpha : {0.2, 0.1, 0.05, 0.025}) {
    CAPTURE(alpha);
    Eigen::VectorXd q = q0 + alpha * p;
    placement.place(q);
    const double deviation = (q - (q0 + alpha * p)).lpNorm<Eigen::Infinity>();
    CHECK(deviation > 0.0);
    if (previous > 0.0) {
      CHECK(previous / deviation == doctest::Approx(4.0).epsilon(0.1));
      ++halvings;
    }
    previous = deviation;
  }
  CHECK(halvings == 3);
}

TEST_CASE("Joint placement: nothing to place without a free joint") {
  // A single X held at its joint: its four segments end free.
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Position}}};
  LinkageProblem problem(RodLinkage(single_x(), test_options(RestShape::Input, 4)), setup);
  REQUIRE(problem.linkage().num_joints() == 1);
  JointChordPlacement placement(problem);
  CHECK(!placement.active());
}

}  // namespace xshell::test
