#include "linkage/graph.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

namespace xshell::test {

TEST_CASE("corner vertices: the extremes along the plan's four diagonals, each once") {
  // A 3 x 2 grid of points, slightly rotated, plus one point inside.
  LineGraph g;
  const double c = std::cos(0.1), s = std::sin(0.1);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j) g.vertices.emplace_back(c * j - s * i, s * j + c * i, 0.3 * j);
  g.vertices.emplace_back(1.0, 0.5, 5.0);  // z plays no part
  // x + y largest: (2, 1); x - y: (2, 0); -x + y: (0, 1); -x - y: (0, 0).
  CHECK(corner_vertices(g) == std::vector<int>{5, 2, 3, 0});

  // A single point is every corner.
  LineGraph one;
  one.vertices.emplace_back(1.0, 2.0, 3.0);
  CHECK(corner_vertices(one) == std::vector<int>{0});
  CHECK(corner_vertices(LineGraph{}).empty());
}

}  // namespace xshell::test
