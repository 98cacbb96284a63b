// Prescribed support displacements (VertexSupport::displacement): the held
// components start at input + displacement and the reactions are those of
// the displaced structure.
#include <doctest/doctest.h>

#include <cmath>

#include "integrators/beam_fixtures.hpp"
#include "linkage/model_error.hpp"
#include "linkage/reactions.hpp"

namespace xshell::test {

namespace {

// The unit beam (E I = 1) clamped at vertex 0; the tip (vertex 1) is held
// by `tip`.
LinkageProblem propped_cantilever(int n, const VertexSupport& tip, double w = 0.01) {
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Orientation}}, tip};
  return unit_beam(n, setup, w);
}

}  // namespace

TEST_CASE("Propped cantilever: a settled tip support reacts with 3 E I delta / L^3") {
  // Clamped at x = 0, tip on a roller in z pushed up by delta (x and y stay
  // free, so no axial force arises): the support force is 3 EI delta / L^3.
  // The clamp holds the first edge (both nodes and its twist), centred on
  // the vertex, so the span is L: the reaction converges to the beam's
  // 3 EI delta / L^3 at O(l^2) (observed 0.26 l^2 at 50 and 100 edges).
  const double delta = 1e-3;
  int checked = 0;
  for (int n : {50, 100}) {
    CAPTURE(n);
    const double l = 1.0 / n;
    LinkageProblem problem =
        propped_cantilever(n, {1, {SupportDof::Z}, Eigen::Vector3d(0, 0, delta)});
    // The solve starts at the displaced position.
    CHECK(problem.vertex_positions()[1].z() == delta);
    REQUIRE(relax(problem, 1e-8).converged());  // EA / EI = 1.2e5: round-off floor near 1e-9
    CHECK(problem.vertex_positions()[1].z() == delta);
    const std::vector<SupportReaction> r = support_reactions(problem);
    REQUIRE(r.size() == 2);
    REQUIRE(r[1].vertex == 1);
    CHECK(std::abs(r[1].force.z() / (3.0 * delta) - 1.0) <= l * l);
    CHECK(std::abs(r[1].force.x()) <= 1e-6 * r[1].force.z());
    // The clamp balances it: -R and the moment R L about the root.
    CHECK(r[0].force.z() == doctest::Approx(-r[1].force.z()).epsilon(1e-6).scale(0.0));
    REQUIRE(r[0].moment.has_value());
    CHECK(r[0].moment->norm() == doctest::Approx(r[1].force.z() * 1.0).epsilon(1e-6).scale(0.0));
    ++checked;
  }
  CHECK(checked == 2);
}

TEST_CASE("A displaced clamp translates the clamped end edge, a displaced joint starts moved") {
  // Clamped free end with "position" and a displacement: both clamped nodes
  // move by it, so the clamped edge keeps its length and direction, and its
  // midpoint, the vertex, moves by the displacement.
  const Eigen::Vector3d d(0.0, 0.002, -0.001);
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}};
  g.edges = {{0, 1}};
  LinkageOptions o;
  o.subdivisions = 10;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = 1e4;
  o.material.section = {SectionShape::Rectangle, 0.05, 0.03};
  StaticsSetup clamp;
  clamp.supports = {{0, {SupportDof::Position, SupportDof::Orientation}, d},
                    {1, {SupportDof::Position}}};
  o.clamped_ends = {0};
  const RodLinkage straight(g, o);
  const LinkageProblem moved(straight, clamp);
  const ElasticRod& rod = moved.linkage().segment(0);
  CHECK((rod.nodes()[0] - (straight.segment(0).nodes()[0] + d)).norm() <= 1e-15);
  CHECK((rod.nodes()[1] - (straight.segment(0).nodes()[1] + d)).norm() <= 1e-15);
  CHECK((moved.vertex_positions()[0] - (g.vertices[0] + d)).norm() <= 1e-15);
  CHECK((rod.nodes()[10] - g.vertices[1]).norm() <= 1e-15);  // the other end stays

  // A joint: its position p starts (and stays) at input + displacement.
  LineGraph x;
  x.vertices = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
  x.edges = {{1, 0}, {0, 2}, {3, 0}, {0, 4}};
  o.subdivisions = 6;
  o.clamped_ends.clear();  // no free end of the X is clamped
  StaticsSetup joint;
  const Eigen::Vector3d dz(0, 0, 0.01);
  joint.supports = {{0, {SupportDof::Position, SupportDof::Orientation}, dz}};
  for (int v = 1; v <= 4; ++v) joint.supports.push_back({v, {SupportDof::Position}});
  LinkageProblem problem(RodLinkage(x, o), joint);
  CHECK((problem.vertex_positions()[0] - dz).norm() <= 1e-15);
  REQUIRE(relax(problem, 1e-10).converged());
  CHECK((problem.vertex_positions()[0] - dz).norm() <= 1e-15);
  // Pushing the centre up: the joint's support pushes up, the four ends pull
  // down, and without loads the reactions balance.
  const std::vector<SupportReaction> r = support_reactions(problem);
  REQUIRE(r.size() == 5);
  CHECK(r[0].force.z() > 0.0);
  const Wrench total = reaction_resultant(r);
  CHECK(total.force.norm() <= 1e-6 * r[0].force.norm());
}

TEST_CASE("A displacement of a component the support leaves free is refused") {
  CHECK_THROWS_AS(propped_cantilever(10, {1, {SupportDof::Z}, Eigen::Vector3d(0, 0.001, 0)}),
                  ModelError);
  CHECK_THROWS_AS(
      propped_cantilever(10, {1, {SupportDof::X, SupportDof::Y}, Eigen::Vector3d(0, 0, 0.001)}),
      ModelError);
  CHECK_NOTHROW(
      propped_cantilever(10, {1, {SupportDof::Position}, Eigen::Vector3d(0.001, 0.001, 0.001)}));
}

TEST_CASE("A support holds input + displacement whatever state the linkage is in") {
  // A restart from a saved state: the linkage is not at its input. The held
  // position is input + displacement all the same (zero displacement too),
  // continuous in the displacement, and the problem says how far it moved
  // the vertex; made again from its own state, it moves nothing.
  LineGraph x;
  x.vertices = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
  x.edges = {{1, 0}, {0, 2}, {3, 0}, {0, 4}};
  LinkageOptions o;
  o.subdivisions = 6;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = 1e4;
  o.material.section = {SectionShape::Rectangle, 0.05, 0.03};
  RodLinkage moved(x, o);
  const Eigen::Vector3d shift(0.3, 0.0, 0.1);
  Eigen::VectorXd q = moved.dofs();
  q.segment<3>(moved.joint_dof_offset(0) + kPosition) += shift;
  moved.set_dofs(q);
  int checked = 0;
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1e-6)}) {
    CAPTURE(d.z());
    StaticsSetup setup;
    setup.supports = {{0, {SupportDof::Position, SupportDof::Orientation}, d}};
    const LinkageProblem problem(moved, setup);
    CHECK((problem.vertex_positions()[0] - (x.vertices[0] + d)).norm() <= 1e-15);
    REQUIRE(problem.support_start_offsets().size() == 1);
    CHECK((problem.support_start_offsets()[0] - (d - shift)).norm() <= 1e-15);
    const LinkageProblem again(problem.linkage(), setup);
    CHECK(again.support_start_offsets()[0].norm() == 0.0);
    CHECK(again.vertex_positions()[0] == problem.vertex_positions()[0]);
    ++checked;
  }
  CHECK(checked == 2);
  // A roller holds (and moves) only its component.
  StaticsSetup roller;
  roller.supports = {{0, {SupportDof::Z}}};
  const LinkageProblem rolled(moved, roller);
  CHECK(rolled.support_start_offsets()[0] == Eigen::Vector3d(0, 0, -0.1));
  CHECK(rolled.vertex_positions()[0].x() == 0.3);
  // The default pin holds its joint where it is.
  const LinkageProblem pinned(moved, StaticsSetup{});
  CHECK(pinned.default_support_vertex() == 0);
  CHECK(pinned.vertex_positions()[0] == x.vertices[0] + shift);
  CHECK(pinned.support_start_offsets()[0].norm() == 0.0);
}

}  // namespace xshell::test
