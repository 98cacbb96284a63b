#include <doctest/doctest.h>
#include <cstdio>
#include "integrators/linkage_objective.hpp"
#include "integrators/newton.hpp"
#include "integrators/dynamics.hpp"
#include "linkage/statics_problem.hpp"
using namespace xshell;
namespace {
LineGraph grid(int n) {
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
}
TEST_CASE("zz scratch linkage") {
  const int n = 4;
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0, 0, -9.81);
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) setup.supports.push_back({corner, {SupportDof::Position}});
  LinkageOptions o;
  o.subdivisions = 6;
  o.material.young_modulus = 2e10;
  o.material.density = 1800;
  o.material.section = {SectionShape::Rectangle, 0.01, 0.007};
  for (LineSearch ls : {LineSearch::Energy, LineSearch::KinsolWithEnergyFallback}) {
    LinkageProblem problem(RodLinkage(grid(n), o), setup);
    LinkageObjective objective(problem);
    NewtonOptions opt;
    opt.gradient_tolerance = 1e-10;
    opt.max_iterations = 200;
    opt.line_search = ls;
    NewtonCallbacks cb;
    cb.on_iteration = [](const NewtonReport& r) {
      std::fprintf(stderr, "it %d E %.15g g %.3e step %.3e fact %ld shift %g els %d t %.3f\n", r.iteration, r.energy,
                   r.gradient_measure, r.step_norm, r.factorizations, r.shift, (int)r.energy_line_search, r.seconds);
    };
    const NewtonResult res = solve_newton(objective, opt, cb);
    std::fprintf(stderr, "status %s reason %s n=%ld iterations %d stable %d\n", to_string(res.status), res.reason.c_str(), (long)objective.size(), res.iterations, (int)res.stable);
  }
}
