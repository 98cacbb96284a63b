// Grids of straight laths for the solver tests: a square grid graph and the
// laths' material (SI units).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "linkage/graph.hpp"
#include "linkage/rod_linkage.hpp"

namespace xshell::test {

// n x n crossings 0.25 m apart in the plane z = 0, joined along x and y.
inline LineGraph square_grid(int n) {
  LineGraph g;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g.vertices.emplace_back(0.25 * j, 0.25 * i, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * n + j;
      if (j + 1 < n) g.edges.push_back({v, v + 1});
      if (i + 1 < n) g.edges.push_back({v, v + n});
    }
  return g;
}

// Straight laths, 10 x 7 mm, E = 20 GPa, density 1800 kg/m^3.
inline LinkageOptions lath_options(int subdivisions = 6) {
  LinkageOptions o;
  o.subdivisions = subdivisions;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = 2e10;
  o.material.density = 1800;
  o.material.section = {SectionShape::Rectangle, 0.01, 0.007};
  return o;
}

// The corners of a roughly rectangular plan (linkage/graph.hpp).
using xshell::corner_vertices;

}  // namespace xshell::test
