// Small linkage graphs covering valences 1-4, planar and not.
#pragma once

#include <cmath>

#include "linkage/rod_linkage.hpp"

namespace xshell::test {

// Two rods crossing at one valence-4 joint; four free ends.
inline LineGraph single_x() {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {-1, -0.6, 0}, {1, 0.7, 0.05}, {-0.7, 1, 0}, {0.8, -1, -0.1}};
  g.edges = {{1, 0}, {0, 2}, {3, 0}, {0, 4}};
  return g;
}

// One rod through a valence-3 joint and a second rod ending there.
inline LineGraph tee() {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {-1, 0.1, 0}, {1.1, 0, 0.2}, {0.2, 1.0, -0.1}};
  g.edges = {{1, 0}, {0, 2}, {0, 3}};
  return g;
}

// A rows x cols grid of vertices with all horizontal and vertical edges:
// valence 2 at the corners, 3 on the sides, 4 inside. `bump` lifts it into a
// non-planar shell; `shear` skews it.
inline LineGraph grid(int rows, int cols, double bump = 0.0, double shear = 0.2) {
  LineGraph g;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const double x = j + shear * i, y = 0.9 * i;
      g.vertices.emplace_back(x, y, bump * std::sin(0.9 * x) * std::cos(0.7 * y));
    }
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int v = i * cols + j;
      if (j + 1 < cols) g.edges.push_back({v, v + 1});
      if (i + 1 < rows) g.edges.push_back({v, v + cols});
    }
  return g;
}

inline LinkageOptions test_options(RestShape rest = RestShape::Input, int subdivisions = 4) {
  LinkageOptions o;
  o.subdivisions = subdivisions;
  o.rest_shape = rest;
  o.material.young_modulus = 100.0;
  o.material.poisson_ratio = 0.3;
  o.material.density = 2.0;
  o.material.section = {SectionShape::Rectangle, 0.08, 0.05};
  return o;
}

}  // namespace xshell::test
