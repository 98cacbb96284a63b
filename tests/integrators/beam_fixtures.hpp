// Straight beams as one-segment linkages, for the engineering results
// (reactions, stresses, buckling) against beam theory.
#pragma once

#include <cmath>

#include "integrators/common/linkage_objective.hpp"
#include "integrators/newton/newton.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell::test {

// A straight rod of length 1 along x as a one-segment linkage, square
// section of side w with E I = 1 (E = 12 / w^4), under `setup` (built with
// the free ends that setup clamps).
inline LinkageProblem unit_beam(int subdivisions, const StaticsSetup& setup, double w = 0.01) {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}};
  g.edges = {{0, 1}};
  LinkageOptions o;
  o.subdivisions = subdivisions;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = 12.0 / std::pow(w, 4);
  o.material.section = {SectionShape::Rectangle, w, w};
  o.clamped_ends = clamped_free_ends(g, setup.supports);
  return LinkageProblem(RodLinkage(g, o), setup);
}

// The unit beam clamped at vertex 0 (its first edge, centred on the vertex,
// held), loaded at the tip (vertex 1).
inline LinkageProblem cantilever_beam(int subdivisions, const Eigen::Vector3d& tip_force,
                                      double w = 0.01) {
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Orientation}}};
  setup.forces = {{1, tip_force}};
  return unit_beam(subdivisions, setup, w);
}

// escape: leave saddles (the default); false for tests of the saddle itself.
inline NewtonOptions tight_newton(double tolerance = 1e-9, bool escape = true) {
  NewtonOptions n;
  n.escape.enabled = escape;
  n.gradient_tolerance = tolerance;
  n.max_iterations = 200;
  n.line_search = LineSearch::Energy;
  return n;
}

inline NewtonResult relax(LinkageProblem& problem, double tolerance = 1e-9, bool escape = true) {
  LinkageObjective objective(problem);
  const NewtonResult result = solve_newton(objective, tight_newton(tolerance, escape));
  if (!result.converged()) MESSAGE(result.reason);
  return result;
}

}  // namespace xshell::test
