#include "integrators/design/vertex_targets.hpp"

#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "linkage/model_error.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell::test {

namespace {

// Two rods crossing at one joint (vertex 0) with four free ends.
LineGraph crossing() {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {-1, -0.6, 0}, {1, 0.7, 0.05}, {-0.7, 1, 0}, {0.8, -1, -0.1}};
  g.edges = {{1, 0}, {0, 2}, {3, 0}, {0, 4}};
  return g;
}

LinkageOptions options(std::vector<int> clamped = {}) {
  LinkageOptions o;
  o.subdivisions = 4;
  o.material.young_modulus = 100.0;
  o.material.section = {SectionShape::Rectangle, 0.08, 0.05};
  o.clamped_ends = std::move(clamped);
  return o;
}

}  // namespace

TEST_CASE("Target fit gradient matches finite differences at joints and free ends") {
  std::mt19937 rng(5);
  int checked = 0;
  for (bool clamped : {false, true}) {
    CAPTURE(clamped);
    RodLinkage linkage(crossing(), options(clamped ? std::vector<int>{3} : std::vector<int>{}));
    linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.02));
    std::vector<VertexTarget> targets;
    for (int v = 0; v < 5; ++v)
      targets.push_back({v, linkage.vertex_position(v) + random_vector(3, rng, 0.1), 1.0 + v});
    const Eigen::VectorXd g = target_fit_gradient(linkage, targets);
    auto fit = [&](const Eigen::VectorXd& r) {
      RodLinkage copy = linkage;
      copy.set_dofs(r);
      return target_fit(copy, targets);
    };
    const DifferenceReport report = check_gradient(fit, linkage.dofs(), g, 1e-6);
    CHECK(report.scale > 0.0);
    CHECK(report.relative_error() <= 1e-8);
    checked += report.compared;
  }
  CHECK(checked > 100);
}

TEST_CASE("Target fit refuses a vertex that is not the linkage's") {
  const RodLinkage linkage(crossing(), options());
  CHECK_THROWS_AS(vertex_position_terms(linkage, 5), ModelError);
  CHECK_THROWS_AS(vertex_position_terms(linkage, -1), ModelError);
  CHECK(vertex_position_terms(linkage, 0).size() == 1);
}

}  // namespace xshell::test
