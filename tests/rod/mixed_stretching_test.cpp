// The stretching's axial forces and Newton's mixed Hessian at the rod level
// (docs/model.md section 9.8).
#include <doctest/doctest.h>

#include "rod/stretching.hpp"
#include "rod_fixtures.hpp"

namespace xshell::test {

namespace {

Eigen::VectorXd axial_forces_at(const ElasticRod& rod, const Eigen::VectorXd& q) {
  ElasticRod r = rod;
  r.set_dofs(q);
  Eigen::VectorXd n(r.num_edges());
  for (int j = 0; j < r.num_edges(); ++j) n[j] = r.axial_force(j);
  return n;
}

// The gradient of F(q) = sum_j c_j |e_j(q)| over the rod's full variables.
Eigen::VectorXd length_sum_gradient(const ElasticRod& rod, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& c) {
  ElasticRod r = rod;
  r.set_dofs(q);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(r.num_dofs());
  for (int j = 0; j < r.num_edges(); ++j) {
    g.segment<3>(ElasticRod::node_dof(j)) -= c[j] * r.tangent(j);
    g.segment<3>(ElasticRod::node_dof(j + 1)) += c[j] * r.tangent(j);
  }
  return g;
}

}  // namespace

TEST_CASE("Axial forces: N = dE/d|e| of each edge, linearized along a velocity") {
  std::mt19937 rng(41);
  int checked = 0;
  for (int trial = 0; trial < 3; ++trial) {
    ElasticRod rod = random_curved_rod(6, rng, anisotropic_stiffness());
    rod.set_stretching_share(0, 0.5);
    perturb(rod, rng, 0.1);
    const Eigen::VectorXd q = rod.dofs();
    const Eigen::VectorXd v = random_vector(rod.num_dofs(), rng);
    const Eigen::VectorXd linear = rod.linearized_axial_forces(v);
    const double h = 1e-6;
    const Eigen::VectorXd rate =
        (axial_forces_at(rod, q + h * v) - axial_forces_at(rod, q - h * v)) / (2.0 * h);
    for (int j = 0; j < rod.num_edges(); ++j) {
      const Eigen::Vector3d e = rod.edge(j);
      const double k = rod.stiffness().stretching * rod.stretching_share(j);
      // The stretching gradient is N t.
      CHECK((stretching_gradient(e, rod.rest_lengths()[j], k) - rod.axial_force(j) * rod.tangent(j))
                .norm() <= 1e-12 * k);
      CHECK(std::abs(linear[j] - rod.axial_force(j) - rate[j]) <= 1e-6 * k);
      ++checked;
    }
    CHECK(rate.cwiseAbs().maxCoeff() > 1e-3 * rod.stiffness().stretching);
  }
  CHECK(checked == 18);
}

TEST_CASE("Mixed rod Hessian: the exact one plus the Hessian of sum_j (sigma_j - N_j) |e_j|") {
  std::mt19937 rng(43);
  int checked = 0;
  for (int trial = 0; trial < 3; ++trial) {
    ElasticRod rod = random_curved_rod(6, rng, anisotropic_stiffness());
    perturb(rod, rng, 0.1);
    const Eigen::VectorXd q = rod.dofs();
    const int n = rod.num_dofs();
    Eigen::VectorXd own(rod.num_edges());
    for (int j = 0; j < rod.num_edges(); ++j) own[j] = rod.axial_force(j);
    const Eigen::VectorXd sigma = own + random_vector(rod.num_edges(), rng, 5.0);
    Eigen::VectorXd g_exact = Eigen::VectorXd::Zero(n), g_mixed = g_exact, g_own = g_exact;
    Eigen::MatrixXd h_exact = Eigen::MatrixXd::Zero(n, n), h_mixed = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd h_own = Eigen::MatrixXd::Zero(n, n);
    rod.add_gradient_and_hessian(g_exact, h_exact);
    rod.add_gradient_and_hessian(g_mixed, h_mixed, &sigma);
    rod.add_gradient_and_hessian(g_own, h_own, &own);
    CHECK(g_mixed == g_exact);
    CHECK(g_own == g_exact);
    CHECK((h_own - h_exact).cwiseAbs().maxCoeff() <= 1e-12 * h_exact.cwiseAbs().maxCoeff());
    const Eigen::VectorXd c = sigma - own;
    const auto grad = [&](const Eigen::VectorXd& y) { return length_sum_gradient(rod, y, c); };
    const DifferenceReport r = check_hessian(grad, q, h_mixed - h_exact, 1e-6);
    CHECK(r.scale > 1.0);
    CHECK(r.relative_error() < 1e-6);
    checked += r.compared;
  }
  CHECK(checked == 3 * 27 * 27);
}

}  // namespace xshell::test
