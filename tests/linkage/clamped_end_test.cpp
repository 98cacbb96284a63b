// Clamped free rod ends (docs/model.md section 8.2): the clamped end edge is
// centred on its vertex, its outer half has no mass, the linkage and its
// supports must agree on which ends are clamped, state files record them,
// and the clamp's reaction balances the loads about the vertex.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "integrators/beam_fixtures.hpp"
#include "io/input_error.hpp"
#include "io/state_file.hpp"
#include "linkage/model_error.hpp"
#include "linkage/reactions.hpp"
#include "linkage_fixtures.hpp"
#include "scratch_directory.hpp"

namespace xshell::test {

namespace {

// A straight rod from a to b as a one-segment linkage.
LineGraph straight_rod(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  LineGraph g;
  g.vertices = {a, b};
  g.edges = {{0, 1}};
  return g;
}

StaticsSetup clamped_at(std::vector<int> vertices) {
  StaticsSetup setup;
  for (int v : vertices)
    setup.supports.push_back({v, {SupportDof::Position, SupportDof::Orientation}});
  return setup;
}

}  // namespace

TEST_CASE(
    "A clamped free end's end edge is centred on its vertex and the other edges fill the rod") {
  const Eigen::Vector3d a(0.1, -0.2, 0.3), b(1.3, 0.4, -0.1);
  const double length = (b - a).norm();
  const Eigen::Vector3d u = (b - a) / length;
  const int n = 7;
  int checked = 0;
  for (const std::vector<int>& clamps : {std::vector<int>{0}, {1}, {0, 1}}) {
    CAPTURE(clamps.size());
    LinkageOptions options = test_options(RestShape::Input, n);
    options.clamped_ends = clamps;
    const RodLinkage linkage(straight_rod(a, b), options);
    const ElasticRod& rod = linkage.segment(0);
    // n edges of one length h fill L + h / 2 per clamped end.
    const double h = length / (n - 0.5 * clamps.size());
    for (int j = 0; j < n; ++j) CHECK(rod.edge(j).norm() == doctest::Approx(h).epsilon(1e-12));
    for (int v : {0, 1}) {
      const bool clamped = std::find(clamps.begin(), clamps.end(), v) != clamps.end();
      const RodLinkage::FreeEnd f = linkage.free_end(v);
      CHECK(f.clamped == clamped);
      const Eigen::Vector3d vertex = v == 0 ? a : b;
      CHECK((linkage.vertex_position(v) - vertex).norm() <= 1e-14);
      const Eigen::Vector3d end = rod.nodes()[f.end_node], next = rod.nodes()[f.next_node];
      if (clamped) {
        // Half an edge outside the rod, half inside, along the rod.
        const Eigen::Vector3d outward = v == 0 ? Eigen::Vector3d(-u) : u;
        CHECK((end - (vertex + 0.5 * h * outward)).norm() <= 1e-14);
        CHECK((next - (vertex - 0.5 * h * outward)).norm() <= 1e-14);
      } else {
        CHECK((end - vertex).norm() == 0.0);
      }
      ++checked;
    }
    // The stress-free input: no energy, no force.
    CHECK(linkage.energy().total() <= 1e-20);
    CHECK(linkage.gradient().norm() <= 1e-12);
    // Mass: rho A L, the clamped edges' outer halves left out.
    const Material& m = options.material;
    const Eigen::VectorXd mass = rod.lumped_mass();
    double total = 0.0;
    for (int k = 0; k < rod.num_nodes(); ++k) total += mass[3 * k];
    CHECK(total ==
          doctest::Approx(m.density * m.section.width * m.section.height * length).epsilon(1e-12));
  }
  CHECK(checked == 6);
}

TEST_CASE("Clamped ends of segments that end at a joint: vertex positions and input energy") {
  // The single X with two free ends clamped: their segments also reach half
  // an edge past the joint.
  LinkageOptions options = test_options(RestShape::Input, 6);
  options.clamped_ends = {3, 1};  // any order
  const RodLinkage linkage(single_x(), options);
  CHECK(linkage.options().clamped_ends == std::vector<int>{1, 3});
  CHECK(linkage.energy().total() <= 1e-20);
  int checked = 0;
  for (int v = 1; v <= 4; ++v) {
    CHECK((linkage.vertex_position(v) - single_x().vertices[v]).norm() <= 1e-14);
    CHECK(linkage.free_end(v).clamped == (v == 1 || v == 3));
    ++checked;
  }
  CHECK(checked == 4);
}

TEST_CASE("The supports must clamp the free ends the linkage was built to clamp") {
  const LineGraph x = single_x();
  StaticsSetup setup = clamped_at({1});
  setup.supports.push_back({2, {SupportDof::Position}});
  setup.supports.push_back({0, {SupportDof::Orientation}});   // a joint: no clamp layout
  setup.supports.push_back({17, {SupportDof::Orientation}});  // out of range: left to the problem
  CHECK(clamped_free_ends(x, setup.supports) == std::vector<int>{1});
  setup.supports.pop_back();

  LinkageOptions options = test_options(RestShape::Input, 5);
  CHECK_THROWS_WITH_AS(LinkageProblem(RodLinkage(x, options), setup),
                       doctest::Contains("built without a clamp"), ModelError);
  options.clamped_ends = {1, 2};
  CHECK_THROWS_WITH_AS(LinkageProblem(RodLinkage(x, options), setup),
                       doctest::Contains("no support fixes its \"orientation\""), ModelError);
  options.clamped_ends = {1};
  CHECK_NOTHROW(LinkageProblem(RodLinkage(x, options), setup));
  // Only free ends can be clamped.
  options.clamped_ends = {0};
  CHECK_THROWS_WITH_AS(RodLinkage(x, options), doctest::Contains("vertex 0 is no free rod end"),
                       ModelError);
  options.clamped_ends = {5};
  CHECK_THROWS_AS(RodLinkage(x, options), ModelError);
}

TEST_CASE("A state file records the clamped ends: a state of another clamp layout is refused") {
  const LineGraph x = single_x();
  LinkageOptions unclamped = test_options(RestShape::Input, 5), clamped = unclamped;
  clamped.clamped_ends = {1};
  const ScratchDirectory dir("clamped-end");
  const std::filesystem::path path = dir / "state.json";
  write_state(path.string(), RodLinkage(x, clamped), Eigen::Vector3d::Zero());
  RodLinkage same(x, clamped), other(x, unclamped);
  CHECK_NOTHROW(read_state(path.string(), same, Eigen::Vector3d::Zero()));
  CHECK_THROWS_WITH_AS(read_state(path.string(), other, Eigen::Vector3d::Zero()),
                       doctest::Contains("belongs to another linkage"), InputError);
  // Without clamps the fingerprint is as before (older states still match).
  write_state(path.string(), RodLinkage(x, unclamped), Eigen::Vector3d::Zero());
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("clamped_ends") == std::string::npos);
  CHECK_THROWS_AS(read_state(path.string(), same, Eigen::Vector3d::Zero()), InputError);
}

TEST_CASE("The clamp's reaction balances a large tip load and the rod's weight about the vertex") {
  // The unit cantilever (E I = 1) under P L^2 / E I = 5 and its own weight
  // W = rho A L g.
  const Eigen::Vector3d load(0.0, 0.0, -5.0), g(0.0, 0.0, -2.0);
  StaticsSetup setup = clamped_at({0});
  setup.forces = {{1, load}};
  setup.gravity = g;
  LineGraph rod = straight_rod(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
  const double w = 0.01;
  LinkageOptions o;
  o.subdivisions = 30;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = 12.0 / std::pow(w, 4);
  o.material.density = 1.0 / (w * w);  // unit mass per length
  o.material.section = {SectionShape::Rectangle, w, w};
  o.clamped_ends = clamped_free_ends(rod, setup.supports);
  LinkageProblem problem(RodLinkage(rod, o), setup);
  REQUIRE(relax(problem, 1e-8).converged());
  const std::vector<SupportReaction> r = support_reactions(problem);
  REQUIRE(r.size() == 1);
  REQUIRE(r[0].moment.has_value());
  CHECK((r[0].position - Eigen::Vector3d::Zero()).norm() <= 1e-15);  // the vertex
  // The weight of exactly the rod's length: the outer half edge has none.
  const Eigen::Vector3d weight = 1.0 * g;
  CHECK((r[0].force + load + weight).norm() <= 1e-7 * load.norm());
  // Moment about the vertex: minus the tip load's and the weight's.
  const Wrench loads = applied_load_resultant(problem);
  CHECK((loads.force - (load + weight)).norm() <= 1e-12 * load.norm());
  CHECK((*r[0].moment + loads.moment).norm() <= 1e-7 * load.norm());
  // The tip load's lever is the tip's displacement from the vertex.
  const Eigen::Vector3d tip = problem.vertex_positions()[1];
  CHECK(tip.x() < 0.9);  // a large deflection
  Eigen::Vector3d weight_moment = Eigen::Vector3d::Zero();
  const ElasticRod& segment = problem.linkage().segment(0);
  const Eigen::VectorXd mass = segment.lumped_mass();
  for (int k = 0; k < segment.num_nodes(); ++k)
    weight_moment += segment.nodes()[k].cross(Eigen::Vector3d(mass[3 * k] * g));
  CHECK((*r[0].moment + tip.cross(load) + weight_moment).norm() <= 1e-7 * load.norm());
}

}  // namespace xshell::test
