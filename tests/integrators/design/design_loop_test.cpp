#include "integrators/design/design_loop.hpp"

#include <doctest/doctest.h>

#include <random>
#include <stdexcept>

#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/deployment.hpp"
#include "integrators/deployment/deployment_fixtures.hpp"

namespace xshell::test {

namespace {

double diagonal(const RodLinkage& linkage) {
  Eigen::AlignedBox3d box;
  for (int v = 0; v < static_cast<int>(linkage.graph().vertices.size()); ++v)
    box.extend(linkage.vertex_position(v));
  return box.diagonal().norm();
}

// The vertices' positions of `problem` deployed by `opening` radians with
// the segment rest lengths `lengths`.
std::vector<VertexTarget> deployed_positions(LinkageProblem problem,
                                             const std::vector<double>& lengths, double angle) {
  problem.set_segment_rest_lengths(lengths);
  DeploymentPlan plan;
  plan.average_angle = angle;
  plan.steps = 10;
  DeploymentOptions options;
  options.newton.gradient_tolerance = 2e-10;
  REQUIRE(deploy(problem, plan, options).status == SolveStatus::Converged);
  std::vector<VertexTarget> targets;
  for (int v = 0; v < static_cast<int>(problem.linkage().graph().vertices.size()); ++v)
    targets.push_back({v, problem.linkage().vertex_position(v), 1.0});
  return targets;
}

}  // namespace

TEST_CASE("Design recovers the rest lengths that deployed a linkage to its target shape") {
  // The dome grid's rest lengths perturbed by up to 5% give the target: its
  // deployed joints. The design starts from the drawing's rest lengths.
  const LinkageProblem drawn = dome_problem(3);
  std::vector<double> perturbed = drawn.linkage().segment_rest_lengths();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> factor(0.95, 1.05);
  for (double& l : perturbed) l *= factor(rng);
  DesignOptions o;
  o.deployed_angle = average_opening_angle(drawn.linkage()) + 0.3;
  o.targets = deployed_positions(drawn, perturbed, o.deployed_angle);
  o.newton.gradient_tolerance = 2e-10;
  DesignObjective objective(drawn, o);
  std::vector<DesignIteration> lines;
  DesignLoopOptions loop;
  loop.on_iteration = [&](const DesignIteration& it) { lines.push_back(it); };
  const DesignLoopResult r = optimize_design(objective, loop);
  CAPTURE(r.reason);
  CHECK(r.status == MinimizerStatus::Converged);
  REQUIRE(r.final.status == DesignStatus::Ok);
  REQUIRE(lines.size() == std::size_t(r.iterations) + 1);
  const double start = lines.front().objective;
  MESSAGE("design: " << r.iterations << " iterations, " << r.evaluations << " evaluations, J "
                     << start << " -> " << r.final.value);
  CHECK(r.final.value <= 1e-4 * start);
  const double size = diagonal(objective.deployed().linkage());
  double worst = 0.0;
  for (const VertexTarget& t : o.targets)
    worst = std::max(
        worst, (objective.deployed().linkage().vertex_position(t.vertex) - t.position).norm());
  MESSAGE("largest distance to the target: " << worst / size << " of the diagonal");
  CHECK(worst <= 1e-4 * size);
  for (std::size_t s = 0; s < perturbed.size(); ++s)
    CHECK(r.lengths[s] == doctest::Approx(perturbed[s]).epsilon(1e-3));
  CHECK(lines.front().terms.fit == doctest::Approx(start));
}

TEST_CASE("Design keeps the rest lengths within their bounds") {
  // A target 30% beyond the drawing cannot be reached with changes of at
  // most 2%: the lengths end on their bounds, the fit better than at the start.
  const LinkageProblem drawn = dome_problem(3);
  DesignOptions o;
  o.deployed_angle = average_opening_angle(drawn.linkage()) + 0.3;
  std::vector<double> stretched = drawn.linkage().segment_rest_lengths();
  for (double& l : stretched) l *= 1.3;
  o.targets = deployed_positions(drawn, stretched, o.deployed_angle);
  o.newton.gradient_tolerance = 2e-10;
  DesignObjective objective(drawn, o);
  DesignLoopOptions loop;
  loop.max_relative_change = 0.02;
  const DesignLoopResult r = optimize_design(objective, loop);
  const std::vector<double>& p0 = objective.start_lengths();
  int at_bound = 0;
  for (std::size_t s = 0; s < p0.size(); ++s) {
    CHECK(r.lengths[s] <= 1.02 * p0[s] * (1 + 1e-12));
    CHECK(r.lengths[s] >= 0.98 * p0[s] * (1 - 1e-12));
    at_bound += r.lengths[s] >= 1.02 * p0[s] * (1 - 1e-6);
  }
  CHECK(at_bound > 0);
  CHECK(r.final.value < r.history.front().objective);
  loop.max_relative_change = 1.0;
  CHECK_THROWS_AS(optimize_design(objective, loop), std::invalid_argument);
}

}  // namespace xshell::test
