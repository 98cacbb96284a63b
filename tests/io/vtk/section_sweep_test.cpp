// Section outlines and node frames of the swept solids.
#include "io/vtk/section_sweep.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "demo_snapshot.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Shoelace formula: positive for a counter-clockwise outline.
double signed_area(const std::vector<Eigen::Vector2d>& outline) {
  double area = 0.0;
  for (size_t j = 0; j < outline.size(); ++j) {
    const Eigen::Vector2d& p = outline[j];
    const Eigen::Vector2d& q = outline[(j + 1) % outline.size()];
    area += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  return area;
}

}  // namespace

TEST_CASE("section outlines: rectangle corners and ellipse polygon, counter-clockwise") {
  int checks = 0;
  const SectionSnapshot rectangle{SectionSnapshot::Shape::Rectangle, 0.3, 0.1};
  const auto corners = section_outline(rectangle, 12);
  REQUIRE(corners.size() == 4);
  XSHELL_COUNTED_CHECK(checks, signed_area(corners) == doctest::Approx(0.3 * 0.1).epsilon(1e-14));
  for (const Eigen::Vector2d& c : corners) {
    XSHELL_COUNTED_CHECK(checks, std::abs(c.x()) == doctest::Approx(0.15).epsilon(1e-14));
    XSHELL_COUNTED_CHECK(checks, std::abs(c.y()) == doctest::Approx(0.05).epsilon(1e-14));
  }

  const SectionSnapshot ellipse{SectionSnapshot::Shape::Ellipse, 0.4, 0.1};
  for (int sides : {3, 12, 31}) {
    CAPTURE(sides);
    const auto polygon = section_outline(ellipse, sides);
    REQUIRE(polygon.size() == static_cast<size_t>(sides));
    const double expected = 0.5 * sides * 0.2 * 0.05 * std::sin(2.0 * kPi / sides);
    XSHELL_COUNTED_CHECK(checks, signed_area(polygon) == doctest::Approx(expected).epsilon(1e-12));
    for (const Eigen::Vector2d& p : polygon)
      XSHELL_COUNTED_CHECK(checks, std::pow(p.x() / 0.2, 2) + std::pow(p.y() / 0.05, 2) ==
                                       doctest::Approx(1.0).epsilon(1e-12));
  }
  CHECK(checks == 1 + 2 * 4 + 3 + (3 + 12 + 31));
}

TEST_CASE("section outlines: invalid sections are rejected") {
  CHECK_THROWS_AS(section_outline({SectionSnapshot::Shape::Rectangle, 0.0, 0.1}, 12),
                  std::invalid_argument);
  CHECK_THROWS_AS(section_outline({SectionSnapshot::Shape::Ellipse, 0.1, -1.0}, 12),
                  std::invalid_argument);
  CHECK_THROWS_AS(section_outline({SectionSnapshot::Shape::Ellipse, 0.1, 0.1}, 2),
                  std::invalid_argument);
}

TEST_CASE("node frames: orthonormal, right-handed, edge frames at the ends") {
  const Snapshot snapshot = demo_snapshot(0.0, 0.7);
  int checks = 0;
  int nodes = 0;
  for (const RodSnapshot& rod : snapshot.rods) {
    const auto frames = node_frames(rod);
    REQUIRE(frames.size() == rod.nodes.size());
    const size_t n = rod.nodes.size() - 1;
    for (size_t k = 0; k <= n; ++k, ++nodes) {
      const NodeFrame& f = frames[k];
      XSHELL_COUNTED_CHECK(checks, std::abs(f.tangent.norm() - 1.0) < 1e-12);
      XSHELL_COUNTED_CHECK(checks, std::abs(f.d1.norm() - 1.0) < 1e-12);
      XSHELL_COUNTED_CHECK(checks, std::abs(f.d1.dot(f.tangent)) < 1e-12);
      XSHELL_COUNTED_CHECK(checks, (f.d1.cross(f.d2) - f.tangent).norm() < 1e-12);
      // The tangent bisects the two edges at the node.
      const Eigen::Vector3d before =
          (rod.nodes[k == 0 ? 1 : k] - rod.nodes[k == 0 ? 0 : k - 1]).normalized();
      const Eigen::Vector3d after =
          (rod.nodes[k == n ? n : k + 1] - rod.nodes[k == n ? n - 1 : k]).normalized();
      XSHELL_COUNTED_CHECK(checks, std::abs(f.tangent.dot(before) - f.tangent.dot(after)) < 1e-12);
    }
    // End nodes keep the (orthonormal) frames of their edges.
    XSHELL_COUNTED_CHECK(checks, (frames.front().d1 - rod.d1.front()).norm() < 1e-12);
    XSHELL_COUNTED_CHECK(checks, (frames.front().d2 - rod.d2.front()).norm() < 1e-12);
    XSHELL_COUNTED_CHECK(checks, (frames.back().d1 - rod.d1.back()).norm() < 1e-12);
    XSHELL_COUNTED_CHECK(checks, (frames.back().d2 - rod.d2.back()).norm() < 1e-12);
  }
  CHECK(nodes == 9 + 7);
  CHECK(checks == 5 * nodes + 4 * 2);
}

TEST_CASE("node frames: a left-handed input frame gives the right-handed one") {
  Snapshot snapshot = demo_snapshot();
  RodSnapshot& rod = snapshot.rods[0];
  for (Eigen::Vector3d& d2 : rod.d2) d2 = -d2;
  const auto frames = node_frames(rod);
  int checks = 0;
  for (const NodeFrame& f : frames)
    XSHELL_COUNTED_CHECK(checks, (f.d1.cross(f.d2) - f.tangent).norm() < 1e-12);
  CHECK(checks == 9);
}

TEST_CASE(
    "node frames: a very short edge keeps its direction, a zero one borrows its neighbour's") {
  Snapshot snapshot = demo_snapshot();
  RodSnapshot& rod = snapshot.rods[0];
  REQUIRE(rod.nodes.size() >= 4);
  // Edge 1 is 3e-12 long (before: "rod 0: edge 1 has zero length", which
  // failed the run's outputs), edge 2 of zero length.
  const Eigen::Vector3d up = rod.d2[1].normalized();
  rod.nodes[2] = rod.nodes[1] + 3e-12 * up;
  const Eigen::Vector3d shift = rod.nodes[2] - rod.nodes[3];
  for (size_t k = 4; k < rod.nodes.size(); ++k) rod.nodes[k] += shift;
  rod.nodes[3] = rod.nodes[2];
  std::vector<NodeFrame> frames;
  REQUIRE_NOTHROW(frames = node_frames(rod));
  // Node 1 bisects edge 0 and the short edge 1 (along `up`, to round-off of
  // the coordinates: 1e-16 / 3e-12).
  const Eigen::Vector3d before = (rod.nodes[1] - rod.nodes[0]).normalized();
  const Eigen::Vector3d short_edge = (rod.nodes[2] - rod.nodes[1]).normalized();
  CHECK((short_edge - up).norm() < 1e-3);
  CHECK((frames[1].tangent - (before + short_edge).normalized()).norm() < 1e-12);
  // Node 2 joins edge 1 and the zero edge 2, which takes edge 1's direction.
  CHECK((frames[2].tangent - short_edge).norm() < 1e-12);
  int checks = 0;
  for (const NodeFrame& f : frames) {
    XSHELL_COUNTED_CHECK(checks, std::abs(f.tangent.norm() - 1.0) < 1e-12);
    XSHELL_COUNTED_CHECK(checks, (f.d1.cross(f.d2) - f.tangent).norm() < 1e-12);
  }
  CHECK(checks == 2 * static_cast<int>(frames.size()));
}

}  // namespace xshell::test
