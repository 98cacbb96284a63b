// The "transform" of the input (linkage/graph_transform.hpp): mirror, scale,
// rotations about x, y, z, translation, in that order.
#include "linkage/graph_transform.hpp"

#include <doctest/doctest.h>

#include <Eigen/LU>
#include <cmath>

namespace xshell::test {

TEST_CASE("Transform: each part alone, and the documented order") {
  const Eigen::Vector3d x(1.0, 2.0, 3.0);
  GraphTransform t;
  CHECK(t.is_identity());
  CHECK(t.apply(x) == x);
  t.mirror = 2;
  CHECK(t.apply(x) == Eigen::Vector3d(1, 2, -3));
  t = {};
  t.scale = 1e-3;  // millimetres to metres
  CHECK((t.apply(x) - 1e-3 * x).norm() < 1e-18);
  t = {};
  t.rotate_deg = {0, 0, 90};  // x -> y, y -> -x
  CHECK((t.apply(x) - Eigen::Vector3d(-2, 1, 3)).norm() < 1e-14);
  t = {};
  t.rotate_deg = {90, 0, 0};  // y -> z, z -> -y
  CHECK((t.apply(x) - Eigen::Vector3d(1, -3, 2)).norm() < 1e-14);
  // All at once: mirror z, scale 2, rotate x 90 then z 90, translate.
  t = {};
  t.mirror = 2;
  t.scale = 2.0;
  t.rotate_deg = {90, 0, 90};
  t.translate = {10, 20, 30};
  // (1, 2, 3) -> (1, 2, -3) -> (2, 4, -6) -> about x: (2, 6, 4) -> about z: (-6, 2, 4).
  CHECK((t.apply(x) - Eigen::Vector3d(4, 22, 34)).norm() < 1e-13);
  CHECK(!t.is_identity());
  CHECK(std::abs(t.linear().determinant() + 8.0) < 1e-12);  // a mirror: orientation reversed
  LineGraph g;
  g.vertices = {x, Eigen::Vector3d::Zero()};
  g.edges = {{0, 1}};
  const LineGraph moved = transformed(g, t);
  CHECK((moved.vertices[0] - t.apply(x)).norm() < 1e-13);
  CHECK(moved.vertices[1] == t.translate);
  CHECK(moved.edges == g.edges);
}

}  // namespace xshell::test
