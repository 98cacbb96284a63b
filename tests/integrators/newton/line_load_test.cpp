// Line loads (a dead load per unit rest length on chosen rods, docs/model.md
// section 4.8): lumped exactly as gravity, acting only on the rods chosen,
// and a cantilever under a uniform load against beam theory, converging at
// second order in the number of edges.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "integrators/beam_fixtures.hpp"
#include "integrators/grid_fixtures.hpp"
#include "linkage/reactions.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell::test {

namespace {

// The unit cantilever (E I = 1, L = 1, clamped at vertex 0) under the line
// load w on its one rod; the tip's displacement from (1, 0, 0).
Eigen::Vector3d tip_under_line_load(int edges, const Eigen::Vector3d& w) {
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Orientation}}};
  setup.line_loads = {{{}, w}};
  // A thick section (EA / EI = 1200): its stretching stays negligible and the
  // round-off floor low enough for a residual far below the loads.
  LinkageProblem problem = unit_beam(edges, setup, 0.1);
  const NewtonResult result = relax(problem, 3e-11);
  REQUIRE(result.converged());
  return problem.vertex_positions()[1] - Eigen::Vector3d(1.0, 0.0, 0.0);
}

}  // namespace

TEST_CASE("Line loads: a load on every rod is gravity's lumping, w = rho A g") {
  LinkageOptions options = lath_options(5);
  const double area = 0.01 * 0.007;
  const Eigen::Vector3d g(0.3, -1.0, -9.81);
  StaticsSetup gravity;
  gravity.gravity = g;
  StaticsSetup line;
  line.line_loads = {{{}, options.material.density * area * g}};
  const RodLinkage linkage(square_grid(3), options);
  const LinkageProblem by_gravity(linkage, gravity), by_line(linkage, line);
  REQUIRE(by_gravity.segment_loads().size() == by_line.segment_loads().size());
  for (std::size_t s = 0; s < by_line.segment_loads().size(); ++s) {
    const Eigen::VectorXd& a = by_gravity.segment_loads()[s];
    const Eigen::VectorXd& b = by_line.segment_loads()[s];
    CHECK((a - b).cwiseAbs().maxCoeff() <= 1e-12 * a.cwiseAbs().maxCoeff());
  }
  // The total is w times the rods' total rest length: the grid's 6 rods of
  // 0.5 m each (terminal edges at joints counted once).
  const Wrench total = applied_load_resultant(by_line);
  CHECK((total.force - 3.0 * options.material.density * area * g).norm() <= 1e-12 * g.norm());
}

TEST_CASE("Line loads: only the rods chosen carry the load, several loads add up") {
  const RodLinkage linkage(square_grid(3), lath_options(4));
  const Eigen::Vector3d w(0.0, 0.0, -2.0);
  StaticsSetup setup;
  setup.line_loads = {{{1}, w}, {{1, 2}, 0.5 * w}};
  const LinkageProblem problem(linkage, setup);
  REQUIRE(linkage.topology().rods.size() == 6);
  std::vector<Eigen::Vector3d> on_rod(6, Eigen::Vector3d::Zero());
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const Eigen::VectorXd& f = problem.segment_loads()[s];
    for (int n = 0; n < linkage.segment(s).num_nodes(); ++n)
      on_rod[linkage.topology().segments[s].rod] += f.segment<3>(3 * n);
  }
  for (int rod : {0, 3, 4, 5}) CHECK(on_rod[rod].norm() == 0.0);
  CHECK((on_rod[1] - 1.5 * 0.5 * w).norm() <= 1e-12);  // each rod is 0.5 m long
  CHECK((on_rod[2] - 0.5 * 0.5 * w).norm() <= 1e-12);
  StaticsSetup bad;
  bad.line_loads = {{{6}, w}};
  CHECK_THROWS_WITH(LinkageProblem(linkage, bad),
                    doctest::Contains("a line load names rod 6, but the linkage has 6 rods"));
}

TEST_CASE("Line loads: a cantilever under a uniform load, w L^4 / 8 E I at second order") {
  // A small load, so that the beam stays linear (w L^3 / E I = 1e-3: the
  // geometric correction is far below the discretization errors compared).
  const double w = 1e-3, exact = w / 8.0;
  const int edges[] = {16, 32, 64, 100};
  double error[4];
  std::string table = "edges  tip deflection  relative error\n";
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d tip = tip_under_line_load(edges[i], Eigen::Vector3d(0, 0, -w));
    error[i] = std::abs(-tip.z() - exact) / exact;
    char row[80];
    std::snprintf(row, sizeof row, "%5d  %.9e  %.3e\n", edges[i], -tip.z(), error[i]);
    table += row;
  }
  MESSAGE(table);
  CHECK(std::log2(error[0] / error[1]) >= 1.8);
  CHECK(std::log2(error[1] / error[2]) >= 1.8);
  CHECK(error[3] <= 1e-4);
}

}  // namespace xshell::test
