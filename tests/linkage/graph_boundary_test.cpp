// The boundary of a linkage graph (linkage/graph_boundary.hpp): the outer
// rim of its drawing over its best-fit plane and its free rod ends.
#include "linkage/graph_boundary.hpp"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <vector>

#include "linkage/model_error.hpp"

namespace xshell::test {

namespace {

// n x n vertices a unit apart in the plane z = 0, joined along x and y.
LineGraph grid(int n) {
  LineGraph g;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g.vertices.emplace_back(j, i, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (j + 1 < n) g.edges.push_back({i * n + j, i * n + j + 1});
      if (i + 1 < n) g.edges.push_back({i * n + j, (i + 1) * n + j});
    }
  return g;
}

std::vector<int> ring_of_grid(int n) {
  std::vector<int> ring;
  for (int v = 0; v < n * n; ++v)
    if (v / n == 0 || v / n == n - 1 || v % n == 0 || v % n == n - 1) ring.push_back(v);
  return ring;
}

}  // namespace

TEST_CASE("Boundary: the outer ring of a grid, not its inside") {
  CHECK(boundary_vertices(grid(4)) == ring_of_grid(4));
  CHECK(boundary_vertices(grid(5)) == ring_of_grid(5));
}

TEST_CASE("Boundary: the same in any plane, after any rotation and mirror") {
  LineGraph g = grid(5);
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  for (Eigen::Vector3d& v : g.vertices) v = r * v + Eigen::Vector3d(10, -3, 7);
  CHECK(boundary_vertices(g) == ring_of_grid(5));
  for (Eigen::Vector3d& v : g.vertices) v.x() = -v.x();
  CHECK(boundary_vertices(g) == ring_of_grid(5));
}

TEST_CASE("Boundary: chains sticking out and free ends are in it, a hole's rim is not") {
  // A 5 x 5 grid without its centre vertex (12): a hole inside, whose rim (the
  // vertices around 12) is not the boundary; a spike out of vertex 2 (top of
  // the picture: y = -1) and a free end poking into the hole from vertex 7.
  LineGraph g = grid(5);
  std::vector<std::array<int, 2>> kept;
  for (const auto& e : g.edges)
    if (e[0] != 12 && e[1] != 12) kept.push_back(e);
  g.edges = kept;
  g.vertices[12] = {2.0, 1.6, 0.0};  // now the free end inside the hole
  g.edges.push_back({7, 12});
  g.vertices.emplace_back(2.0, -1.0, 0.0);  // 25: the spike's end
  g.edges.push_back({2, 25});
  std::vector<int> expected = ring_of_grid(5);
  expected.push_back(12);
  expected.push_back(25);
  std::sort(expected.begin(), expected.end());
  CHECK(boundary_vertices(g) == expected);
}

TEST_CASE("Boundary: a drawing whose edges cross has none") {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  g.edges = {{0, 1}, {2, 3}};
  CHECK_THROWS_AS(boundary_vertices(g), ModelError);
  CHECK_THROWS_WITH(boundary_vertices(LineGraph{}), doctest::Contains("no edge"));
}

}  // namespace xshell::test
