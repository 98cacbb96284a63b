#include <doctest/doctest.h>

#include <cmath>

#include "integrators/beam_fixtures.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/grid_fixtures.hpp"
#include "integrators/newton/newton.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell::test {

using xshell::test::lath_options;
using xshell::test::square_grid;

namespace {

// The unit cantilever of beam_fixtures.hpp (E I = 1, clamped at vertex 0).
LinkageProblem cantilever(int subdivisions, const Eigen::Vector3d& tip_force) {
  return xshell::test::cantilever_beam(subdivisions, tip_force);
}

NewtonOptions tight(double tolerance = 1e-9) {
  NewtonOptions n;
  n.gradient_tolerance = tolerance;
  n.max_iterations = 200;
  n.line_search = LineSearch::Energy;
  return n;
}

// One loop of four joints (the 2 x 2 grid, laths 0.25 scale m long) clamped
// at a corner, folding and swinging down under its weight.
LinkageProblem hanging_loop(double scale) {
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0, 0, -9.81);
  setup.supports.push_back({0, {SupportDof::Position, SupportDof::Orientation}});
  LinkageOptions laths = lath_options(8);
  laths.material.young_modulus = 2e9;
  laths.material.density = 1000;
  laths.material.section = {SectionShape::Rectangle, 0.02, 0.01};
  LineGraph loop = square_grid(2);
  for (Eigen::Vector3d& v : loop.vertices) v *= scale;
  return LinkageProblem(RodLinkage(loop, laths), setup);
}

}  // namespace

// The cantilever and the clamped-free column against the elastica, with their
// convergence order: clamped_elastica_test.cpp.

TEST_CASE(
    "Euler buckling of a clamped-free column: straight is stable below P_cr, unstable above") {
  const double p_cr = M_PI * M_PI / 4.0;  // E I = 1, L = 1
  int cases = 0;
  for (double factor : {0.85, 1.15}) {
    LinkageProblem problem = cantilever(40, Eigen::Vector3d(-factor * p_cr, 0, 0));
    LinkageObjective objective(problem);
    NewtonOptions options = tight();
    options.escape.enabled = false;  // the straight state itself is studied
    const NewtonResult result = solve_newton(objective, options);
    REQUIRE(result.converged());
    // Still straight: the exactly axial load leaves no lateral force.
    CHECK(std::abs(problem.vertex_positions()[1].z()) < 1e-12);
    CHECK(result.stable == (factor < 1.0));
    ++cases;
  }
  CHECK(cases == 2);
}

TEST_CASE("Linkage under gravity: converged below tolerance, symmetric, quadratic at the end") {
  const int n = 4;
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0, 0, -9.81);
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1})
    setup.supports.push_back({corner, {SupportDof::Position}});
  LinkageProblem problem(RodLinkage(square_grid(n), lath_options()), setup);
  LinkageObjective objective(problem);
  std::vector<double> measures;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport& r) { measures.push_back(r.gradient_measure); };
  NewtonOptions options = tight(1e-8);
  options.max_chord_corrections = 0;  // Newton's own rate, checked below
  const NewtonResult result = solve_newton(objective, options, callbacks);
  CAPTURE(result.reason);
  CAPTURE(result.iterations);
  REQUIRE(result.converged());
  CHECK(result.stable);
  CHECK(problem.gradient_measure() <= 1e-8);
  CHECK(problem.vertex_positions()[5].z() < -1e-4);  // it sags
  // Mirror symmetry about the grid's two axes.
  const auto x = problem.vertex_positions();
  const double diagonal = problem.length_scale();
  int pairs = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d a = x[i * n + j], b = x[i * n + (n - 1 - j)],
                            c = x[(n - 1 - i) * n + j];
      const double centre = 0.25 * (n - 1) / 2.0;  // of the input grid, in x and y
      CHECK(std::abs(a.x() + b.x() - 2.0 * centre) < 1e-8 * diagonal);
      CHECK(std::abs(a.z() - b.z()) < 1e-8 * diagonal);
      CHECK(std::abs(a.y() + c.y() - 2.0 * centre) < 1e-8 * diagonal);
      CHECK(std::abs(a.z() - c.z()) < 1e-8 * diagonal);
      ++pairs;
    }
  CHECK(pairs == n * n);
  // Quadratic convergence: once below 1e-3, each measure is at most a
  // modest constant times the square of the previous one.
  int quadratic_steps = 0;
  for (size_t k = 1; k < measures.size(); ++k)
    if (measures[k - 1] < 1e-3 && measures[k - 1] > 1e-8) {
      CHECK(measures[k] <= 1e3 * measures[k - 1] * measures[k - 1]);
      ++quadratic_steps;
    }
  CHECK(quadratic_steps >= 1);
}

TEST_CASE("A zero-energy mechanism (flat grid of straight rods, no load) is converged at once") {
  LinkageProblem problem(RodLinkage(square_grid(4), lath_options()), StaticsSetup{});
  CHECK(problem.default_support_vertex() >= 0);
  LinkageObjective objective(problem);
  const NewtonResult result = solve_newton(objective, tight());
  CHECK(result.converged());
  CHECK(result.iterations == 0);
  CHECK(problem.energy().total() == doctest::Approx(0.0));
}

TEST_CASE("Mixed Hessian: a hanging loop reaches the same stable equilibrium in fewer iterations") {
  // Laths 2 m long: the stretching's axial forces change by their own size
  // between iterates.
  int iterations[2] = {0, 0};
  std::vector<Eigen::Vector3d> end[2];
  double energy[2] = {0.0, 0.0};
  for (bool mixed : {false, true}) {
    LinkageProblem problem = hanging_loop(8.0);
    LinkageObjective objective(problem);
    NewtonOptions options = tight(1e-8);
    options.mixed_hessian = mixed;
    const NewtonResult result = solve_newton(objective, options);
    CAPTURE(mixed);
    REQUIRE(result.converged());
    CHECK(result.stable);
    CHECK(!problem.mixed_hessian());  // the exact Hessian again after the solve
    iterations[mixed] = result.iterations;
    end[mixed] = problem.vertex_positions();
    energy[mixed] = problem.energy().total();
    CHECK(problem.vertex_positions()[3].z() < -0.1);  // it hangs
  }
  MESSAGE("hanging loop: " << iterations[0] << " Newton iterations with the exact Hessian, "
                           << iterations[1] << " with the mixed one");
  // The same equilibrium (positions to 1 um, of laths 2 m long).
  for (size_t v = 0; v < end[0].size(); ++v) CHECK((end[1][v] - end[0][v]).norm() < 1e-6);
  CHECK(energy[1] == doctest::Approx(energy[0]).epsilon(1e-9));
  CHECK(iterations[1] < iterations[0]);
}

TEST_CASE("Mixed Hessian: KINSOL's own steps leave the exact Hessian for the next iteration") {
  // The loop above with laths 0.5 m long: shifted steps on the energy
  // (mixed after them), the others by KINSOL's line search, which creeps
  // on this loop (no convergence in 200 iterations, as with the exact
  // Hessian throughout): the steps' kinds are what is checked.
  LinkageProblem problem = hanging_loop(2.0);
  LinkageObjective objective(problem);
  NewtonOptions options = tight(1e-8);
  options.line_search = LineSearch::KinsolWithEnergyFallback;
  int kinsol_steps = 0, energy_steps = 0;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport& r) {
    if (r.iteration == 0) return;
    CHECK(problem.mixed_hessian() == r.energy_line_search);
    ++(r.energy_line_search ? energy_steps : kinsol_steps);
  };
  const NewtonResult result = solve_newton(objective, options, callbacks);
  MESSAGE("KINSOL's line search: " << kinsol_steps << " steps, the energy's: " << energy_steps);
  CHECK(result.iterations == kinsol_steps + energy_steps);
  CHECK(!problem.mixed_hessian());
  CHECK(kinsol_steps > 0);
  CHECK(energy_steps > 0);
}

}  // namespace xshell::test
