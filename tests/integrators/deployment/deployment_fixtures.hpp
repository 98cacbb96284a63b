// Small linkages for the deployment tests: an n x n grid of rods (spacing
// 0.25 m, centred at the origin) lifted onto a dome z = -k (x^2 + y^2),
// stress-free as drawn, or flat with straight rods (a mechanism). Vertex
// (i, j) is i * n + j at (x_j, y_i); with n odd the centre joint is pinned
// (position and orientation), so the mirror x <-> y of the grid is a mirror
// symmetry of every deployed state.
#pragma once

#include <Eigen/Core>

#include "linkage/statics_problem.hpp"

namespace xshell::test {

inline LineGraph dome_grid(int n, double k) {
  LineGraph g;
  const double spacing = 0.25, half = 0.5 * (n - 1) * spacing;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -half + spacing * j, y = -half + spacing * i;
      g.vertices.emplace_back(x, y, -k * (x * x + y * y));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * n + j;
      if (j + 1 < n) g.edges.push_back({v, v + 1});
      if (i + 1 < n) g.edges.push_back({v, v + n});
    }
  return g;
}

inline LinkageOptions lath_material(RestShape rest) {
  LinkageOptions o;
  o.subdivisions = 5;
  o.rest_shape = rest;
  o.material.young_modulus = 2e10;
  o.material.poisson_ratio = 0.3;
  o.material.section = {SectionShape::Rectangle, 0.01, 0.007};
  return o;
}

// The dome grid, stress-free as drawn, centre joint pinned.
inline LinkageProblem dome_problem(int n = 3, double k = 0.8) {
  StaticsSetup setup;
  setup.supports = {{(n * n) / 2, {SupportDof::Position, SupportDof::Orientation}}};
  return LinkageProblem(RodLinkage(dome_grid(n, k), lath_material(RestShape::Input)), setup);
}

// A flat grid of straight rods: a mechanism that opens without energy.
inline LinkageProblem flat_mechanism(int n = 3) {
  StaticsSetup setup;
  setup.supports = {{(n * n) / 2, {SupportDof::Position, SupportDof::Orientation}}};
  return LinkageProblem(RodLinkage(dome_grid(n, 0.0), lath_material(RestShape::Straight)), setup);
}

}  // namespace xshell::test
