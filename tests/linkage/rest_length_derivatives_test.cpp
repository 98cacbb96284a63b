#include <doctest/doctest.h>

#include <random>
#include <string>

#include "finite_differences.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {

struct NamedGraph {
  const char* name;
  LineGraph graph;
};

// Central differences in p_s of E and grad E at fixed reduced unknowns,
// against the analytic dE/dp and d(grad E)/dp; returns the entries compared.
int check_rest_length_derivatives(const RodLinkage& linkage, double tolerance) {
  const std::vector<double> p = linkage.segment_rest_lengths();
  const Eigen::VectorXd de = linkage.energy_rest_length_derivative();
  const Eigen::MatrixXd dg = Eigen::MatrixXd(linkage.gradient_rest_length_derivative());
  REQUIRE(de.size() == linkage.num_segments());
  REQUIRE(dg.rows() == linkage.num_dofs());
  REQUIRE(dg.cols() == linkage.num_segments());
  auto at = [&](int s, double h) {
    RodLinkage copy = linkage;
    std::vector<double> q = p;
    q[s] += h;
    copy.set_segment_rest_lengths(q);
    return copy;
  };
  DifferenceReport energy, gradient;
  energy.scale = de.cwiseAbs().maxCoeff();
  gradient.scale = dg.cwiseAbs().maxCoeff();
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const double h = 1e-6 * p[s];
    const RodLinkage plus = at(s, h), minus = at(s, -h);
    const double fd = (plus.energy().total() - minus.energy().total()) / (2 * h);
    energy.max_abs_error = std::max(energy.max_abs_error, std::abs(fd - de[s]));
    const Eigen::VectorXd column = (plus.gradient() - minus.gradient()) / (2 * h);
    gradient.max_abs_error =
        std::max(gradient.max_abs_error, (column - dg.col(s)).cwiseAbs().maxCoeff());
    energy.compared += 1;
    gradient.compared += static_cast<int>(column.size());
  }
  CHECK(energy.scale > 0.0);
  CHECK(gradient.scale > 0.0);
  CHECK(energy.relative_error() <= tolerance);
  CHECK(gradient.relative_error() <= tolerance);
  MESSAGE("dE/dp relative error " << energy.relative_error() << ", d(grad E)/dp "
                                  << gradient.relative_error());
  return energy.compared + gradient.compared;
}

}  // namespace

TEST_CASE("Rest length derivatives of the energy and its gradient match finite differences") {
  const std::vector<NamedGraph> graphs = {{"single X", single_x()},
                                          {"tee", tee()},
                                          {"grid 3x3", grid(3, 3)},
                                          {"curved grid 3x3", grid(3, 3, 0.4)}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> factor(0.9, 1.1);
  int checked = 0, cases = 0;
  for (const NamedGraph& ng : graphs)
    for (RestShape rest : {RestShape::Input, RestShape::Straight})
      for (JointKind kind : {JointKind::Rotation, JointKind::EdgeVectors}) {
        const std::string name = ng.name;
        const std::string shape = rest == RestShape::Input ? "input" : "straight";
        const std::string joints = kind == JointKind::Rotation ? "rotation" : "edge vectors";
        CAPTURE(name);
        CAPTURE(shape);
        CAPTURE(joints);
        LinkageOptions options = test_options(rest);
        options.joint_kind = kind;
        RodLinkage linkage(ng.graph, options);
        std::vector<double> p = linkage.segment_rest_lengths();
        for (double& l : p) l *= factor(rng);
        linkage.set_segment_rest_lengths(p);
        linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.03));
        checked += check_rest_length_derivatives(linkage, 1e-6);
        ++cases;
      }
  CHECK(cases == 16);
  CHECK(checked > 16 * 30);
}

TEST_CASE("Mixed rest length derivative: column s lives on segment s's unknowns") {
  const RodLinkage linkage(grid(3, 3), test_options(RestShape::Straight));
  const Eigen::SparseMatrix<double> dg = linkage.gradient_rest_length_derivative();
  int checked = 0;
  for (int s = 0; s < linkage.num_segments(); ++s) {
    std::vector<bool> local(linkage.num_dofs(), false);
    for (int k = 0; k < linkage.segment(s).num_dofs(); ++k)
      if (linkage.reduced_index(s, k) >= 0) local[linkage.reduced_index(s, k)] = true;
    const SegmentTopology& seg = linkage.topology().segments[s];
    for (int side = 0; side < 2; ++side)
      if (seg.joint[side] >= 0)
        for (int k = 0; k < 9; ++k) local[linkage.joint_dof_offset(seg.joint[side]) + k] = true;
    for (Eigen::SparseMatrix<double>::InnerIterator it(dg, s); it; ++it) {
      CHECK(local[it.row()]);
      ++checked;
    }
  }
  CHECK(checked > linkage.num_segments());
}

}  // namespace xshell::test
