// Linkages whose segments have different materials and sections
// (LinkageOptions::segment_materials): stiffness, masses and derivatives
// follow each segment's own material.
#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {

// Segment s gets one of three materials that differ in modulus, Poisson
// ratio, density and section (shape and both sides).
LinkageOptions mixed_options(const LineGraph& graph, RestShape rest) {
  LinkageOptions o = test_options(rest);
  Material a = o.material, b = o.material, c = o.material;
  b.young_modulus = 260.0;
  b.poisson_ratio = 0.2;
  b.density = 5.0;
  b.section = {SectionShape::Rectangle, 0.05, 0.11};
  c.young_modulus = 60.0;
  c.density = 0.5;
  c.section = {SectionShape::Ellipse, 0.12, 0.06};
  const Material choice[3] = {a, b, c};
  for (size_t s = 0; s < graph.edges.size(); ++s) o.segment_materials.push_back(choice[s % 3]);
  return o;
}

}  // namespace

TEST_CASE("Mixed materials: each segment's stiffness and masses come from its own material") {
  const LineGraph graph = grid(3, 4, 0.4);
  const LinkageOptions options = mixed_options(graph, RestShape::Input);
  const RodLinkage linkage(graph, options);
  REQUIRE(linkage.num_segments() == static_cast<int>(options.segment_materials.size()));
  int checked = 0;
  for (int s = 0; s < linkage.num_segments(); ++s) {
    CAPTURE(s);
    const Material& m = options.segment_materials[s];
    CHECK(linkage.segment_material(s).young_modulus == m.young_modulus);
    CHECK(linkage.segment_material(s).section.width == m.section.width);
    const RodStiffness expected = stiffness(m);
    const RodStiffness& k = linkage.segment(s).stiffness();
    CHECK(k.stretching == expected.stretching);
    CHECK(k.bending1 == expected.bending1);
    CHECK(k.bending2 == expected.bending2);
    CHECK(k.twisting == expected.twisting);
    // Lumped translational mass: density x area x the segment's rest length,
    // the shared terminal edges counted half.
    const ElasticRod& rod = linkage.segment(s);
    const Eigen::VectorXd mass = rod.lumped_mass();
    double total = 0.0;
    for (int n = 0; n < rod.num_nodes(); ++n) total += mass[3 * n];
    double rest = 0.0;
    for (int j = 0; j < rod.num_edges(); ++j) rest += rod.rest_lengths()[j];
    const SegmentTopology& seg = linkage.topology().segments[s];
    const double shared = 0.5 * ((seg.joint[0] >= 0 ? rod.rest_lengths().front() : 0.0) +
                                 (seg.joint[1] >= 0 ? rod.rest_lengths().back() : 0.0));
    CHECK(total ==
          doctest::Approx(m.density * expected.area * (rest - shared)).epsilon(1e-12).scale(0.0));
    ++checked;
  }
  CHECK(checked == 17);
  // The three materials really differ (the checks above could not pass by
  // comparing one material with itself).
  CHECK(linkage.segment(0).stiffness().bending1 != linkage.segment(1).stiffness().bending1);
  CHECK(linkage.segment(1).stiffness().bending1 != linkage.segment(2).stiffness().bending1);
}

TEST_CASE("Mixed materials: the linkage Hessian matches finite differences of its gradient") {
  std::mt19937 rng(7);
  int checked = 0;
  for (const LineGraph& graph : {tee(), grid(3, 4, 0.4)}) {
    for (RestShape rest : {RestShape::Input, RestShape::Straight}) {
      RodLinkage linkage(graph, mixed_options(graph, rest));
      linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.03));
      const Eigen::VectorXd r = linkage.dofs();
      const auto f = [&](const Eigen::VectorXd& y) {
        RodLinkage copy = linkage;
        copy.set_dofs(y);
        return copy.energy().total();
      };
      const auto g = [&](const Eigen::VectorXd& y) {
        RodLinkage copy = linkage;
        copy.set_dofs(y);
        return copy.gradient();
      };
      const Eigen::VectorXd grad = linkage.gradient();
      const Eigen::MatrixXd hess = Eigen::MatrixXd(linkage.hessian());
      const DifferenceReport rg = check_gradient(f, r, grad, 1e-6);
      const DifferenceReport rh = check_hessian(g, r, hess, 1e-6);
      CHECK(rg.scale > 0.0);
      CHECK(rh.scale > 0.0);
      CHECK(rg.relative_error() < 1e-6);
      CHECK(rh.relative_error() < 1e-5);
      checked += rg.compared + rh.compared;

      // The energy is not that of the uniform material: the mix is in use.
      LinkageOptions uniform = linkage.options();
      uniform.segment_materials.clear();
      RodLinkage same_shape(graph, uniform);
      same_shape.set_dofs(r);
      CHECK(std::abs(same_shape.energy().total() - linkage.energy().total()) >
            1e-3 * std::abs(linkage.energy().total()));
    }
  }
  CHECK(checked > 4 * 100);
}

TEST_CASE("Mixed materials: a material list of the wrong length is refused") {
  LinkageOptions o = test_options();
  o.segment_materials.assign(3, o.material);  // single_x has 4 segments
  CHECK_THROWS(RodLinkage(single_x(), o));
}

}  // namespace xshell::test
