// The branch choice under loads (DeploymentOptions::follow_unloaded_twin):
// a clamped-free column compressed beyond Euler's load, with a short
// crossing rod at a joint halfway along it whose opening angle is
// deployed. Without a sideways load the start is a saddle, left on the side
// of the buckling direction; a small sideways load against that direction
// makes the column buckle to the load's side, and the twin (the same
// problem without that component) brings the deployment to the user's side.
#include <doctest/doctest.h>

#include <cmath>

#include "integrators/deployment/deployment.hpp"
#include "integrators/stability/branch_bias.hpp"

namespace xshell::test {

namespace {

constexpr double kCritical = M_PI * M_PI / 4.0;  // clamped-free, E I = 1, L = 1

// Vertices: 0 the clamped base, 1 the joint, 2 the loaded tip (the column
// along x), 3 and 4 the crossing rod's free ends. The column's tip carries
// 1.2 P_cr along -x and `sideways` along z.
LinkageProblem column_through_joint(double sideways) {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {0.5, -0.05, 0}, {0.5, 0.05, 0}};
  g.edges = {{0, 1}, {1, 2}, {3, 1}, {1, 4}};
  LinkageOptions o;
  o.subdivisions = 10;
  o.rest_shape = RestShape::Straight;
  // E I = 1 for bending out of the linkage's plane (the weak axis).
  const double h = 0.01, w = 1.2 * h;
  o.material.young_modulus = 12.0 / (w * h * h * h);
  o.material.density = 1.0 / (w * h);
  o.material.section = {SectionShape::Rectangle, w, h};
  StaticsSetup s;
  s.supports = {{0, {SupportDof::Position, SupportDof::Orientation}},
                {1, {SupportDof::OpeningAngle}}};
  s.forces = {{2, Eigen::Vector3d(-1.2 * kCritical, 0.0, sideways)}};
  o.clamped_ends = clamped_free_ends(g, s.supports);
  return LinkageProblem(RodLinkage(g, o), s);
}

DeploymentPlan open_joint(const LinkageProblem& problem) {
  DeploymentPlan plan;
  plan.joint_angles = {{0, problem.linkage().joint(0).opening_angle() + 0.2}};
  plan.steps = 2;
  return plan;
}

DeploymentOptions options(DeploymentSolver solver, const Eigen::Vector3d& direction) {
  DeploymentOptions o;
  o.solver = solver;
  o.buckling_direction = direction;
  o.newton.gradient_tolerance = 1e-8;
  o.newton.max_iterations = 200;
  o.dynamics.stopping.gradient_tolerance = 1e-8;
  return o;
}

struct Outcome {
  DeploymentResult result;
  double tip_z = 0.0;
};

Outcome deploy_column(double sideways, const DeploymentOptions& o) {
  LinkageProblem problem = column_through_joint(sideways);
  Outcome out;
  out.result = deploy(problem, open_joint(problem), o);
  CAPTURE(out.result.reason);
  REQUIRE(out.result.converged());
  for (const DeploymentStep& step : out.result.steps) CHECK(step.stable);
  out.tip_z = problem.vertex_positions()[2].z();
  return out;
}

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

}  // namespace

TEST_CASE("Without sideways loads the column leaves its saddle on the user's side, with no twin") {
  for (const double sign : {1.0, -1.0}) {
    const Outcome o = deploy_column(0.0, options(DeploymentSolver::Newton, sign * kUp));
    CHECK(o.result.saddles_escaped.size() >= 1);
    CHECK(o.result.branch_switch_step == -1);
    CHECK(sign * o.tip_z > 0.1);  // buckled: the elastica's deflection is 0.35 L at 1.2 P_cr
  }
}

TEST_CASE("A sideways load against the buckling direction: the twin brings the user's branch") {
  const double push = -0.02 * kCritical;  // down, against the default +z
  const Outcome chosen = deploy_column(push, options(DeploymentSolver::Newton, kUp));
  CHECK(chosen.result.branch_switch_step == 0);
  CHECK(chosen.tip_z > 0.1);

  DeploymentOptions off = options(DeploymentSolver::Newton, kUp);
  off.follow_unloaded_twin = false;
  const Outcome loads_side = deploy_column(push, off);
  CHECK(loads_side.result.branch_switch_step == -1);
  CHECK(loads_side.tip_z < -0.1);
  // The user's branch works against the load: higher in energy.
  CHECK(chosen.result.energy > loads_side.result.energy);

  const Outcome down = deploy_column(push, options(DeploymentSolver::Newton, -kUp));
  CHECK(down.result.branch_switch_step == -1);  // the load pushes along the direction
  CHECK(down.tip_z == doctest::Approx(loads_side.tip_z).epsilon(1e-8));
}

TEST_CASE("Damped dynamics takes the twin's branch to Newton's state") {
  const double push = -0.02 * kCritical;
  const Outcome newton = deploy_column(push, options(DeploymentSolver::Newton, kUp));
  const Outcome dynamics = deploy_column(push, options(DeploymentSolver::Dynamics, kUp));
  CHECK(dynamics.result.branch_switch_step == 0);
  CHECK(dynamics.tip_z == doctest::Approx(newton.tip_z).epsilon(1e-6));
}

}  // namespace xshell::test
