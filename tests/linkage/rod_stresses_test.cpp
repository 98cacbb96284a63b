#include "linkage/rod_stresses.hpp"

#include <doctest/doctest.h>

#include <cmath>

#include "integrators/beam_fixtures.hpp"
#include "linkage/reactions.hpp"

namespace xshell::test {

namespace {

// A cantilever of length 1 along x, w x h rectangle, clamped at vertex 0;
// the tip load is set after construction, along a director of the rod.
LinkageProblem rectangular_cantilever(int n, double w, double h, double young, int director,
                                      double load, double strength) {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}};
  g.edges = {{0, 1}};
  LinkageOptions o;
  o.subdivisions = n;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = young;
  o.material.section = {SectionShape::Rectangle, w, h};
  o.material.strength = strength;
  o.clamped_ends = {0};
  RodLinkage linkage(g, o);
  const Frame<double> frame = linkage.segment(0).material_frame(0);
  const Eigen::Vector3d d = director == 1 ? frame.d1.values() : frame.d2.values();
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Orientation}}};
  setup.forces = {{1, load * d}};
  return LinkageProblem(std::move(linkage), setup);
}

}  // namespace

TEST_CASE("Cantilever: bending moments and the largest bending stress follow beam theory") {
  const int n = 40;
  const double w = 0.012, h = 0.005, young = 7.0e9, strength = 2.0e6;
  const double l = 1.0 / n;
  // The clamped edge is centred on the root vertex: the n edges of length
  // l_e fill L + l_e / 2, node i >= 1 at s = (i - 1/2) l_e.
  const double l_e = 1.0 / (n - 0.5);
  int checked = 0;
  for (int director : {1, 2}) {
    CAPTURE(director);
    // Bending towards d1 is about d2 (I_d2 = w^3 h / 12), towards d2 about d1.
    const double inertia = director == 1 ? w * w * w * h / 12.0 : w * h * h * h / 12.0;
    const double c = director == 1 ? 0.5 * w : 0.5 * h;
    const double load = 1e-3 * young * inertia;  // P L^2 / EI = 1e-3: the small-load limit
    LinkageProblem problem = rectangular_cantilever(n, w, h, young, director, load, strength);
    REQUIRE(relax(problem).converged());
    const LinkageStresses s = linkage_stresses(problem.linkage());
    REQUIRE(s.segments.size() == 1);
    const std::vector<EdgeStress>& edges = s.segments[0];
    REQUIRE(edges.size() == static_cast<size_t>(n));
    // Root moment from the reaction: exactly P L.
    const SupportReaction r = support_reactions(problem)[0];
    CHECK(r.moment->norm() == doctest::Approx(load * 1.0).epsilon(1e-6).scale(0.0));
    // Along the span M(s) = P (L - s) at the edge midpoints s = k l_e, and
    // at the first bending vertex (s = l_e / 2) for the clamped edge.
    for (int k = 0; k < n - 1; ++k) {
      const double s_k = k == 0 ? 0.5 * l_e : k * l_e;
      const double m = director == 1 ? edges[k].forces.moment1 : edges[k].forces.moment2;
      const double other = director == 1 ? edges[k].forces.moment2 : edges[k].forces.moment1;
      CHECK(std::abs(m) == doctest::Approx(load * (1.0 - s_k)).epsilon(1e-3).scale(0.0));
      CHECK(std::abs(other) <= 1e-6 * load);
      CHECK(std::abs(edges[k].forces.torque) <= 1e-6 * load);
      ++checked;
    }
    // The largest bending stress, at the root: M c / I with M = P (L - l_e / 2),
    // the beam's root value P L c / I to within half the held edge.
    const double sigma = load * (1.0 - 0.5 * l_e) * c / inertia;
    CHECK(s.max_normal_stress.value == doctest::Approx(sigma).epsilon(1e-3).scale(0.0));
    CHECK(s.max_normal_stress.segment == 0);
    CHECK(s.max_normal_stress.edge == 0);
    CHECK(s.max_normal_stress.value ==
          doctest::Approx(load * c / inertia).epsilon(0.6 * l).scale(0.0));
    // Utilisation: the equivalent stress over the strength, largest at the root.
    REQUIRE(s.max_utilisation.has_value());
    CHECK(s.max_utilisation->value == doctest::Approx(edges[0].equivalent / strength).scale(0.0));
    CHECK(s.max_utilisation->edge == 0);
    // Axial force: a transverse tip load leaves the beam (to first order) unstretched.
    CHECK(s.max_axial_force.value <= 1e-3 * load);
  }
  CHECK(checked == 2 * (n - 1));
}

TEST_CASE("Axial force and stress of a rod in tension") {
  // N = P in every edge but the clamped one, which the support holds rigid.
  const double w = 0.01, h = 0.004;
  LinkageProblem pulled = rectangular_cantilever(10, w, h, 1e9, 1, 0.0, 0.0);
  {
    StaticsSetup setup;
    setup.supports = {{0, {SupportDof::Orientation}}};
    setup.forces = {{1, Eigen::Vector3d(50.0, 0, 0)}};
    pulled =
        LinkageProblem(RodLinkage(pulled.linkage().graph(), pulled.linkage().options()), setup);
  }
  REQUIRE(relax(pulled).converged());
  const LinkageStresses s = linkage_stresses(pulled.linkage());
  int checked = 0;
  for (size_t k = 1; k < s.segments[0].size(); ++k) {
    const EdgeStress& e = s.segments[0][k];
    CHECK(e.forces.axial == doctest::Approx(50.0).epsilon(1e-9));
    CHECK(e.stresses.axial == doctest::Approx(50.0 / (w * h)).epsilon(1e-9));
    CHECK(e.stresses.max_normal == doctest::Approx(50.0 / (w * h)).epsilon(1e-6));
    ++checked;
  }
  CHECK(checked == 9);
  CHECK(!s.max_utilisation.has_value());  // no strength given
}

TEST_CASE("Two rods with different sections: stresses follow each rod's own section") {
  // Two parallel cantilevers of length 1 (vertices 0-1 and 2-3), clamped at
  // 0 and 2, each with its own modulus, section and strength, each loaded at
  // its tip towards its own d1 by P = 1e-3 E I (the small-load limit). At
  // the root edge (centred on the clamped vertex) M = P (L - l_e / 2), l_e
  // the edge length, and sigma = M c / I with the rod's own c and I.
  const int n = 40;
  const double l_e = 1.0 / (n - 0.5);
  struct Beam {
    double young, w, h, strength;
  };
  const Beam beams[2] = {{7.0e9, 0.012, 0.005, 2.0e6}, {2.0e10, 0.03, 0.008, 9.0e6}};
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  g.edges = {{0, 1}, {2, 3}};
  LinkageOptions o;
  o.subdivisions = n;
  o.rest_shape = RestShape::Straight;
  for (const Beam& b : beams) {
    Material m;
    m.young_modulus = b.young;
    m.section = {SectionShape::Rectangle, b.w, b.h};
    m.strength = b.strength;
    o.segment_materials.push_back(m);
  }
  o.material = o.segment_materials[0];  // unused: every segment has its own
  o.clamped_ends = {0, 2};
  RodLinkage linkage(g, o);
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Orientation}}, {2, {SupportDof::Orientation}}};
  double load[2], sigma[2];
  for (int s = 0; s < 2; ++s) {
    const double inertia = beams[s].w * beams[s].w * beams[s].w * beams[s].h / 12.0;  // I_d2
    load[s] = 1e-3 * beams[s].young * inertia;
    sigma[s] = load[s] * (1.0 - 0.5 * l_e) * (0.5 * beams[s].w) / inertia;
    setup.forces.push_back({2 * s + 1, load[s] * linkage.segment(s).material_frame(0).d1.values()});
  }
  LinkageProblem problem(std::move(linkage), setup);
  REQUIRE(relax(problem).converged());
  const LinkageStresses stresses = linkage_stresses(problem.linkage());
  REQUIRE(stresses.segments.size() == 2);
  int checked = 0;
  for (int s = 0; s < 2; ++s) {
    CAPTURE(s);
    const EdgeStress& root = stresses.segments[s][0];
    // (scale 0: relative tolerances, the loads are small numbers.)
    CHECK(std::abs(root.forces.moment1) ==
          doctest::Approx(load[s] * (1.0 - 0.5 * l_e)).epsilon(1e-3).scale(0.0));
    CHECK(root.stresses.max_normal == doctest::Approx(sigma[s]).epsilon(1e-3).scale(0.0));
    CHECK(root.utilisation.has_value());
    if (root.utilisation)
      CHECK(*root.utilisation ==
            doctest::Approx(root.equivalent / beams[s].strength).epsilon(1e-12).scale(0.0));
    ++checked;
  }
  CHECK(checked == 2);
  // The two sections give stresses far apart (sigma = 1e-3 E c), so the
  // checks above tell the sections apart; the largest is in the stiffer rod.
  CHECK(sigma[1] > 5.0 * sigma[0]);
  CHECK(stresses.max_normal_stress.segment == 1);
  CHECK(stresses.max_normal_stress.rod == problem.linkage().topology().segments[1].rod);
  REQUIRE(stresses.max_utilisation.has_value());
  const double u0 = *stresses.segments[0][0].utilisation, u1 = *stresses.segments[1][0].utilisation;
  CHECK(stresses.max_utilisation->value ==
        doctest::Approx(std::max(u0, u1)).epsilon(1e-12).scale(0.0));
}

}  // namespace xshell::test
