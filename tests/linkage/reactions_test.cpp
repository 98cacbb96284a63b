#include "linkage/reactions.hpp"

#include <doctest/doctest.h>

#include "integrators/beam_fixtures.hpp"
#include "linkage/linkage_fixtures.hpp"

namespace xshell::test {

namespace {

// Reactions plus loads: force and moment about the origin, relative to the
// loads' own size (force scale F, moment scale F L).
void check_balance(const LinkageProblem& problem, int& checked) {
  const std::vector<SupportReaction> reactions = support_reactions(problem);
  const Wrench loads = applied_load_resultant(problem);
  const Wrench supports = reaction_resultant(reactions);
  const double f = loads.force.norm();
  REQUIRE(f > 0.0);
  CAPTURE(loads.force.transpose());
  CAPTURE(supports.force.transpose());
  CAPTURE(loads.moment.transpose());
  CAPTURE(supports.moment.transpose());
  CHECK((loads.force + supports.force).norm() <= 1e-9 * f);
  CHECK((loads.moment + supports.moment).norm() <= 1e-9 * f * problem.length_scale());
  // Not trivially balanced: the supports carry the loads.
  CHECK(supports.force.norm() >= 0.5 * f);
  checked += 2;
}

}  // namespace

TEST_CASE("Support reactions balance the applied forces and moments") {
  int checked = 0;
  SUBCASE("grid under gravity and point loads on pins and a clamp (rotation joints)") {
    StaticsSetup setup;
    setup.gravity = Eigen::Vector3d(0.3, -0.2, -9.81);
    setup.forces = {{4, Eigen::Vector3d(0.02, 0.01, -0.05)},
                    {7, Eigen::Vector3d(-0.01, 0.03, 0.02)}};
    setup.supports = {{0, {SupportDof::Position, SupportDof::Orientation}},
                      {2, {SupportDof::Position}},
                      {6, {SupportDof::Z, SupportDof::X}},
                      {8, {SupportDof::Position}}};
    LinkageProblem problem(RodLinkage(grid(3, 3, 0.3), test_options(RestShape::Straight, 5)),
                           setup);
    const NewtonResult result = relax(problem);
    REQUIRE(result.converged());
    check_balance(problem, checked);
    const std::vector<SupportReaction> r = support_reactions(problem);
    REQUIRE(r.size() == 4);
    CHECK(r[0].moment.has_value());
    CHECK(!r[1].moment.has_value());
    CHECK(r[2].force.y() == 0.0);  // a roller free along y takes no force along y
  }
  SUBCASE("edge-vector joints with a fixed orientation") {
    StaticsSetup setup;
    setup.gravity = Eigen::Vector3d(0.0, 0.004, -0.0981);
    setup.supports = {{0, {SupportDof::Position, SupportDof::Orientation}},
                      {2, {SupportDof::Position}},
                      {6, {SupportDof::Position}},
                      {8, {SupportDof::Position}}};
    LinkageOptions options = test_options(RestShape::Input, 5);
    options.joint_kind = JointKind::EdgeVectors;
    LinkageProblem problem(RodLinkage(grid(3, 3, 0.3), options), setup);
    const NewtonResult result = relax(problem);
    REQUIRE(result.converged());
    check_balance(problem, checked);
  }
  SUBCASE("free rod ends clamped and pinned, oblique loads (a twisted, bent X)") {
    StaticsSetup setup;
    setup.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
    setup.forces = {{2, Eigen::Vector3d(0.01, 0.02, -0.03)}};
    setup.supports = {
        {1, {SupportDof::Orientation}}, {3, {SupportDof::Position}}, {4, {SupportDof::Position}}};
    LinkageOptions options = test_options(RestShape::Input, 6);
    options.clamped_ends = {1};
    LinkageProblem problem(RodLinkage(single_x(), options), setup);
    const NewtonResult result = relax(problem);
    REQUIRE(result.converged());
    check_balance(problem, checked);
    CHECK(support_reactions(problem)[0].moment->norm() > 0.0);
  }
  CHECK(checked == 2);
}

TEST_CASE("Cantilever: the reaction is the tip load and the root moment its lever") {
  const Eigen::Vector3d load(0, 0, -1e-3);  // small: P L^2 / EI = 1e-3
  LinkageProblem problem = cantilever_beam(20, load);
  REQUIRE(relax(problem).converged());
  const std::vector<SupportReaction> r = support_reactions(problem);
  REQUIRE(r.size() == 1);
  CHECK(r[0].vertex == 0);
  CHECK((r[0].force + load).norm() <= 1e-6 * load.norm());
  REQUIRE(r[0].moment.has_value());
  // M = -(L e_x) x P about the clamp: P L about y.
  const Eigen::Vector3d expected = -Eigen::Vector3d(1, 0, 0).cross(load);
  CHECK((*r[0].moment - expected).norm() <= 1e-6 * expected.norm());
}

}  // namespace xshell::test
