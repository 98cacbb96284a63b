// Edge-vector joints (docs/model.md section 5.4) as a cross-check of the rotation
// joints (docs/model.md section 5.2): the same linkage, loads and supports, solved by Newton
// (energy line search) to a gradient measure of 1e-8 in each
// parametrization, reaches the same equilibrium. Supports are the same
// constraint in both: "position" pins, and a constrained joint is
// {position, orientation, opening_angle} with rotation joints and
// {position, orientation} with edge-vector joints (both rod directions
// held, lengths free).
#include <doctest/doctest.h>

#include <optional>
#include <string>

#include "integrators/common/linkage_objective.hpp"
#include "integrators/grid_fixtures.hpp"
#include "integrators/newton/newton.hpp"
#include "linkage/linkage_fixtures.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell::test {

using xshell::test::lath_options;
using xshell::test::square_grid;

namespace {

struct LoadCase {
  std::string name;
  LineGraph graph;
  LinkageOptions options;
  StaticsSetup setup;            // supports as for rotation joints
  std::vector<int> constrained;  // vertices with a constrained joint
};

std::vector<LoadCase> load_cases() {
  std::vector<LoadCase> cases;
  {  // Valences 2-4, gravity, four corners pinned.
    LoadCase c{"4x4 grid of straight laths under gravity, corners pinned",
               square_grid(4),
               lath_options(),
               {},
               {}};
    c.setup.gravity = Eigen::Vector3d(0, 0, -9.81);
    for (int corner : {0, 3, 12, 15}) c.setup.supports.push_back({corner, {SupportDof::Position}});
    cases.push_back(c);
  }
  {  // Curved shell at rest as built, point loads, three corners pinned.
    LoadCase c{"curved 3x4 grid, point loads, three corners pinned",
               test::grid(3, 4, 0.4),
               test::test_options(RestShape::Input, 5),
               {},
               {}};
    c.setup.forces = {{5, Eigen::Vector3d(0, 0, -4e-4)},
                      {6, Eigen::Vector3d(1e-4, 0, -3e-4)},
                      {10, Eigen::Vector3d(0, 2e-4, 1e-4)}};
    for (int corner : {0, 3, 8}) c.setup.supports.push_back({corner, {SupportDof::Position}});
    cases.push_back(c);
  }
  {  // Valence 4 and free ends: a clamped X under tip loads and gravity.
    LoadCase c{"single X clamped at its joint, tip loads and gravity",
               test::single_x(),
               test::test_options(RestShape::Straight, 8),
               {},
               {0}};
    c.setup.gravity = Eigen::Vector3d(0, 0, -2e-3);
    c.setup.forces = {{1, Eigen::Vector3d(0, 0, 2e-4)},
                      {2, Eigen::Vector3d(0, 1e-4, -2e-4)},
                      {4, Eigen::Vector3d(1e-4, 0, 1e-4)}};
    cases.push_back(c);
  }
  {  // Valence 3: a clamped tee under tip loads.
    LoadCase c{"tee clamped at its joint, tip loads",
               test::tee(),
               test::test_options(RestShape::Input, 8),
               {},
               {0}};
    c.setup.forces = {{1, Eigen::Vector3d(0, 0, -2e-4)}, {3, Eigen::Vector3d(1e-4, 0, 2e-4)}};
    cases.push_back(c);
  }
  {  // A grid hanging from its clamped central joint under gravity.
    LoadCase c{"3x3 grid hanging from its clamped central joint",
               test::grid(3, 3, 0.2),
               test::test_options(RestShape::Straight, 6),
               {},
               {4}};
    c.setup.gravity = Eigen::Vector3d(0, 0, -1e-3);
    cases.push_back(c);
  }
  return cases;
}

struct Solved {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::optional<double>> angles;
  double energy = 0.0;
  double diagonal = 0.0;
  long iterations = 0;
};

Solved solve(const LoadCase& c, JointKind kind) {
  LinkageOptions options = c.options;
  options.joint_kind = kind;
  StaticsSetup setup = c.setup;
  for (int v : c.constrained) {
    VertexSupport s{v, {SupportDof::Position, SupportDof::Orientation}};
    if (kind == JointKind::Rotation) s.fix.push_back(SupportDof::OpeningAngle);
    setup.supports.push_back(s);
  }
  LinkageProblem problem(RodLinkage(c.graph, options), setup);
  LinkageObjective objective(problem);
  NewtonOptions newton;
  newton.gradient_tolerance = 1e-8;
  newton.max_iterations = 100;
  newton.line_search = LineSearch::Energy;
  const NewtonResult result = solve_newton(objective, newton);
  CAPTURE(result.reason);
  REQUIRE(result.converged());
  CHECK(problem.gradient_measure() <= 1e-8);
  return {problem.vertex_positions(), problem.opening_angles(), problem.energy().total(),
          problem.length_scale(), result.iterations};
}

}  // namespace

TEST_CASE("Edge-vector and rotation joints reach the same equilibrium (Newton, tolerance 1e-8)") {
  int cases = 0, vertices = 0;
  double worst_position = 0.0, worst_energy = 0.0, worst_angle = 0.0;
  for (const LoadCase& c : load_cases()) {
    CAPTURE(c.name);
    const Solved rotation = solve(c, JointKind::Rotation);
    const Solved edges = solve(c, JointKind::EdgeVectors);
    // The loads did something: the equilibrium is away from the input.
    double moved = 0.0;
    for (size_t v = 0; v < c.graph.vertices.size(); ++v)
      moved = std::max(moved, (rotation.vertices[v] - c.graph.vertices[v]).norm());
    CHECK(moved > 1e-3 * rotation.diagonal);
    CHECK(rotation.energy != 0.0);
    double position = 0.0, angle = 0.0;
    for (size_t v = 0; v < c.graph.vertices.size(); ++v) {
      position =
          std::max(position, (rotation.vertices[v] - edges.vertices[v]).norm() / rotation.diagonal);
      REQUIRE(rotation.angles[v].has_value() == edges.angles[v].has_value());
      if (rotation.angles[v])
        angle = std::max(angle, std::abs(*rotation.angles[v] - *edges.angles[v]));
      ++vertices;
    }
    const double energy = std::abs(rotation.energy - edges.energy) / std::abs(rotation.energy);
    CHECK(position <= 1e-6);
    CHECK(energy <= 1e-8);
    CHECK(angle <= 1e-6);
    MESSAGE(c.name << ": Newton iterations " << rotation.iterations << " (rotation) / "
                   << edges.iterations << " (edge vectors); moved " << moved / rotation.diagonal
                   << " diagonals; differences: vertices " << position << " diagonals, energy "
                   << energy << " relative, angles " << angle << " rad");
    worst_position = std::max(worst_position, position);
    worst_energy = std::max(worst_energy, energy);
    worst_angle = std::max(worst_angle, angle);
    ++cases;
  }
  CHECK(cases == 5);
  CHECK(vertices == 16 + 12 + 5 + 4 + 9);
  MESSAGE("worst over " << cases << " cases: vertices " << worst_position << " diagonals, energy "
                        << worst_energy << " relative, opening angles " << worst_angle << " rad");
}

}  // namespace xshell::test
