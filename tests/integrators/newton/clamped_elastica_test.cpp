// A clamp at a free rod end acts at its vertex (docs/model.md section 8.2):
// the cantilever and the clamped-free column against the inextensible
// elastica (elastica.hpp), directly, without extrapolation, converging at
// second order in the number of edges. The rods are thin (EA / EI = 1.2e7 per
// unit length squared) so that their stretching stays far below the
// discretization errors compared.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "integrators/beam_fixtures.hpp"
#include "integrators/elastica.hpp"
#include "integrators/stability/stability_analysis.hpp"

namespace xshell::test {

namespace {

constexpr double kThin = 3e-3;  // section side: E I = 1, E A = 12 / kThin^2
// Gradient tolerance (forces over E I / L^2): the stiff stretching puts the
// round-off floor near 1e-8.
constexpr double kTolerance = 1e-7;

// The unit cantilever (clamped at vertex 0, tip at vertex 1, E I = 1, L = 1)
// relaxed under `force` at the tip; the tip's displacement from (1, 0, 0).
Eigen::Vector3d relaxed_tip(int edges, const Eigen::Vector3d& force) {
  LinkageProblem problem = cantilever_beam(edges, force, kThin);
  const NewtonResult result = relax(problem, kTolerance);
  REQUIRE(result.converged());
  CHECK(result.stable);
  return problem.vertex_positions()[1] - Eigen::Vector3d(1.0, 0.0, 0.0);
}

double order(double coarse_error, double fine_error) {
  return std::log2(coarse_error / fine_error);
}

}  // namespace

TEST_CASE(
    "The elastica references: the closed form agrees with shooting and the tabulated values") {
  // Mattiasson (1981), tip deflection v / L at alpha = P L^2 / E I.
  const double alphas[] = {1.0, 2.0, 5.0, 10.0};
  const double tabulated[] = {0.30172, 0.49346, 0.71379, 0.81061};
  int checked = 0;
  for (int i = 0; i < 4; ++i) {
    CAPTURE(alphas[i]);
    const ElasticaTip closed = cantilever_elastica(alphas[i]);
    const ElasticaTip shot = cantilever_elastica_by_shooting(alphas[i]);
    CHECK(std::abs(closed.deflection - shot.deflection) < 1e-9);
    CHECK(std::abs(closed.shortening - shot.shortening) < 1e-9);
    CHECK(std::abs(closed.tip_angle - shot.tip_angle) < 1e-9);
    CHECK(std::abs(closed.deflection - tabulated[i]) <= 5e-6);
    ++checked;
  }
  CHECK(checked == 4);
  // Small loads: beam theory, v / L = alpha / 3.
  CHECK(cantilever_elastica(1e-4).deflection == doctest::Approx(1e-4 / 3.0).epsilon(1e-4));
  // The post-buckled clamped-free column: no deflection at P_cr, and the
  // first-order expansion 2 k / K ~ (4 / pi) sqrt(2 (P / P_cr - 1)) just above.
  CHECK(postbuckled_tip_deflection(1.0) < 1e-6);
  CHECK(postbuckled_tip_deflection(1.0 + 1e-6) ==
        doctest::Approx(4.0 / M_PI * std::sqrt(2e-6)).epsilon(1e-3));
  CHECK(postbuckled_tip_deflection(1.1) == doctest::Approx(0.5085).epsilon(1e-4));
}

TEST_CASE("Cantilever under a tip load: second-order convergence to the elastica") {
  const int edges[] = {16, 32, 64, 100};
  std::string table = "alpha  edges  tip deflection  error / L\n";
  int checked = 0;
  for (double alpha : {1.0, 2.0, 5.0, 10.0}) {
    CAPTURE(alpha);
    const double exact = cantilever_elastica(alpha).deflection;
    double error[4];
    for (int i = 0; i < 4; ++i) {
      const double deflection = -relaxed_tip(edges[i], Eigen::Vector3d(0, 0, -alpha)).z();
      error[i] = std::abs(deflection - exact);
      char row[96];
      std::snprintf(row, sizeof row, "%5.1f  %5d  %14.8f  %9.2e\n", alpha, edges[i], deflection,
                    error[i]);
      table += row;
    }
    const double order_16_32 = order(error[0], error[1]), order_32_64 = order(error[1], error[2]);
    char row[96];
    std::snprintf(row, sizeof row, "       orders: 16-32 %.3f, 32-64 %.3f\n", order_16_32,
                  order_32_64);
    table += row;
    CHECK(order_16_32 >= 1.8);
    CHECK(order_32_64 >= 1.8);
    CHECK(error[3] < 1e-3);
    ++checked;
  }
  MESSAGE(table);
  CHECK(checked == 4);
}

TEST_CASE("Long strides: the cantilever from straight in a few Newton iterations") {
  // From straight, the Newton step turns the rod's edges far: along the
  // line q0 + alpha p that stretches them (by sec(angle) - 1), and the stiff
  // stretching (E A / E I = 1.3e6 per unit length squared) cuts the steps
  // short; along the edge-turning path (docs/model.md section 9.8) it does
  // not. Target: at most 15 iterations at P L^2 / E I = 1 and 10.
  int checked = 0;
  for (double alpha : {1.0, 10.0}) {
    CAPTURE(alpha);
    int iterations[2] = {0, 0};
    for (bool follow : {true, false}) {
      LinkageProblem problem = cantilever_beam(100, Eigen::Vector3d(0, 0, -alpha), kThin);
      LinkageObjective objective(problem);
      NewtonOptions options = tight_newton(kTolerance);
      options.follow_path = follow;
      const NewtonResult result = solve_newton(objective, options);
      REQUIRE(result.converged());
      CHECK(result.stable);
      const double deflection = -problem.vertex_positions()[1].z();
      CHECK(std::abs(deflection - cantilever_elastica(alpha).deflection) < 1e-3);
      iterations[follow ? 0 : 1] = result.iterations;
    }
    MESSAGE("P L^2 / E I = " << alpha << ": " << iterations[0] << " Newton iterations along the "
                             << "path, " << iterations[1] << " along the line");
    CHECK(iterations[0] <= 15);
    CHECK(iterations[1] > 2 * iterations[0]);
    ++checked;
  }
  CHECK(checked == 2);
}

TEST_CASE("Clamped-free column: the Euler load at the clamp's vertex") {
  // E I = 1, L = 1: P_cr = pi^2 / 4.
  const double p_cr = M_PI * M_PI / 4.0;
  LinkageProblem problem = cantilever_beam(100, Eigen::Vector3d(-0.5 * p_cr, 0, 0), kThin);
  REQUIRE(relax(problem, kTolerance).converged());
  const StabilityAnalysis a = analyse_stability(problem);
  REQUIRE(a.unloaded_converged);
  REQUIRE(a.buckling.status == BucklingStatus::Found);
  const double predicted = a.buckling.load_factor * 0.5;
  MESSAGE("linearized buckling load / P_cr at 100 edges: " << predicted);
  CHECK(std::abs(predicted - 1.0) < 5e-3);
  // The straight column's stability changes within 0.5 % of P_cr.
  int cases = 0;
  for (double factor : {0.995, 1.005}) {
    CAPTURE(factor);
    LinkageProblem column = cantilever_beam(100, Eigen::Vector3d(-factor * p_cr, 0, 0), kThin);
    const NewtonResult result = relax(column, kTolerance, /*escape=*/false);
    REQUIRE(result.converged());
    CHECK(result.stable == (factor < 1.0));
    ++cases;
  }
  CHECK(cases == 2);
}

TEST_CASE("Clamped-free column at 1.1 P_cr: the post-buckled tip deflection of the elastica") {
  const double load = 1.1 * M_PI * M_PI / 4.0;
  const double exact = postbuckled_tip_deflection(1.1);
  // A lateral imperfection buckles the column; the exactly axial load then
  // holds it in the buckled equilibrium.
  LinkageProblem imperfect = cantilever_beam(100, Eigen::Vector3d(-load, 0, 0.01 * load), kThin);
  REQUIRE(relax(imperfect, kTolerance).converged());
  StaticsSetup axial;
  axial.supports = imperfect.supports();
  axial.forces = {{1, Eigen::Vector3d(-load, 0, 0)}};
  LinkageProblem column(imperfect.linkage(), axial);
  // (Not asserted stable: with a square section the buckled shape may turn
  // about the column's axis, a zero mode.)
  REQUIRE(relax(column, kTolerance).converged());
  const Eigen::Vector3d tip = column.vertex_positions()[1];
  const double deflection = std::hypot(tip.y(), tip.z());
  MESSAGE("post-buckled tip deflection at 100 edges: " << deflection << " (elastica " << exact
                                                       << ")");
  CHECK(tip.z() > 0.0);  // on the imperfection's side
  CHECK(std::abs(deflection / exact - 1.0) < 5e-3);
}

}  // namespace xshell::test
