#include "linkage/joint_forces.hpp"

#include <doctest/doctest.h>

#include "integrators/beam_fixtures.hpp"
#include "linkage/linkage_fixtures.hpp"
#include "linkage/reactions.hpp"

namespace xshell::test {

TEST_CASE(
    "Joint forces: an L of two rods pinned at a corner carries the tip load through the pin") {
  // Rod A along x from the clamp (vertex 0) to the corner (vertex 1), rod B
  // along y from the corner to a free tip (vertex 2) loaded out of plane.
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  g.edges = {{0, 1}, {1, 2}};
  const Eigen::Vector3d load(0, 0, -2e-4);
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Orientation}}};
  setup.forces = {{2, load}};
  LinkageOptions options = test_options(RestShape::Input, 8);
  options.clamped_ends = {0};
  LinkageProblem problem(RodLinkage(g, options), setup);
  REQUIRE(relax(problem).converged());
  const std::vector<JointForce> forces = joint_forces(problem);
  REQUIRE(forces.size() == 1);
  const JointForce& f = forces[0];
  CHECK(f.vertex == 1);
  // Which of A, B is the loaded rod (the one with the free tip)?
  const int tip_rod = problem.linkage().topology().segments[1].rod;
  const int b = f.rod[1] == tip_rod ? 1 : 0, a = 1 - b;
  // The pin holds the tip rod against the load, and the clamped rod gets the opposite.
  CHECK((f.force_on[b] + load).norm() <= 1e-6 * load.norm());
  CHECK((f.force_on[a] - load).norm() <= 1e-6 * load.norm());
  // Moment on the tip rod about the corner: minus the load's, r x P with r
  // from the corner to the tip, about an in-plane axis (the pin turns freely
  // about the normal).
  REQUIRE(f.moment_on.has_value());
  const Eigen::Vector3d r =
      problem.linkage().vertex_position(2) - problem.linkage().vertex_position(1);
  const Eigen::Vector3d expected = -r.cross(load);
  CHECK(((*f.moment_on)[b] - expected).norm() <= 1e-5 * expected.norm());
  CHECK(((*f.moment_on)[a] + expected).norm() <= 1e-5 * expected.norm());
}

TEST_CASE("Joint forces balance at every pin: A + B = joint load + support reaction") {
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0.3, -0.2, -9.81);
  setup.forces = {{4, Eigen::Vector3d(0.02, 0.01, -0.05)}, {7, Eigen::Vector3d(-0.01, 0.03, 0.02)}};
  setup.supports = {{0, {SupportDof::Position, SupportDof::Orientation}},
                    {2, {SupportDof::Position}},
                    {6, {SupportDof::Position}},
                    {8, {SupportDof::Position}}};
  LinkageProblem problem(RodLinkage(grid(3, 3, 0.3), test_options(RestShape::Straight, 5)), setup);
  REQUIRE(relax(problem).converged());
  const std::vector<SupportReaction> reactions = support_reactions(problem);
  int checked = 0, loaded_pins = 0;
  for (const JointForce& f : joint_forces(problem)) {
    Eigen::Vector3d external = Eigen::Vector3d::Zero();
    for (const PointLoad& p : setup.forces)
      if (p.vertex == f.vertex) external += p.force;
    for (const SupportReaction& r : reactions)
      if (r.vertex == f.vertex) external += r.force;
    const double scale = f.force_on[0].norm() + f.force_on[1].norm();
    CAPTURE(f.vertex);
    CHECK((f.force_on[0] + f.force_on[1] - external).norm() <= 1e-9 * scale);
    if (external.norm() == 0.0) CHECK(f.force_on[0].norm() > 0.0);  // a pin that carries something
    if (external.norm() > 0.0) ++loaded_pins;
    ++checked;
  }
  CHECK(checked == 9);
  CHECK(loaded_pins == 6);
}

}  // namespace xshell::test
