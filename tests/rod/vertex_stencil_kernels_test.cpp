// The fast bending-twisting kernels (closed-form gradient, Hessian as its
// Jacobian by first-order AD) against the reference second-order AD kernel,
// at random stencils: random edges, thetas, rest curvatures and twists, and
// source frames away from the current tangents (exactness away from a
// source-frame update is the point of the finite-transport formulation).
#include <doctest/doctest.h>

#include <random>

#include "rod/vertex_stencil.hpp"
#include "rod_fixtures.hpp"

namespace xshell::test {

namespace {

struct RandomStencil {
  VertexDofs q;
  VertexStencil s;
};

// `offset` sets how far the source tangents are from the current ones (0:
// right after an update).
RandomStencil random_stencil(std::mt19937& rng, double offset) {
  RandomStencil c;
  const Eigen::Vector3d x0 = random_vector(3, rng);
  Eigen::Vector3d e0, e1;
  do {
    e0 = random_vector(3, rng, 1.5);
    e1 = random_vector(3, rng, 1.5);
  } while (e0.norm() < 0.2 || e1.norm() < 0.2 || e0.normalized().dot(e1.normalized()) < -0.8);
  c.q << x0, x0 + e0, x0 + e0 + e1, random_vector(2, rng, 3.0);
  const Eigen::Vector3d e[2] = {e0, e1};
  for (int j = 0; j < 2; ++j) {
    const Eigen::Vector3d t =
        (e[j].normalized() + offset * Eigen::Vector3d(random_vector(3, rng))).normalized();
    c.s.source[j].tangent = t;
    c.s.source[j].d1 = Eigen::Vector3d(random_vector(3, rng)).cross(t).normalized();
  }
  for (auto& side : c.s.rest_kappa)
    for (double& k : side) k = random_vector(1, rng, 1.0)[0];
  c.s.rest_twist = random_vector(1, rng, 1.0)[0];
  c.s.twist_hint = random_vector(1, rng, 0.5)[0];
  c.s.voronoi_length = 0.5 + std::abs(random_vector(1, rng)[0]);
  c.s.bending1 = 1.7;
  c.s.bending2 = 0.6;
  c.s.twisting = 0.9;
  return c;
}

}  // namespace

TEST_CASE("Fast vertex kernels equal the second-order AD kernel at random stencils") {
  std::mt19937 rng(11);
  int compared = 0, stencils = 0;
  for (double offset : {0.0, 0.3, 0.9}) {
    for (int trial = 0; trial < 40; ++trial) {
      const RandomStencil c = random_stencil(rng, offset);
      VertexGradient g_ad, g_fast, g_only;
      VertexHessian h_ad, h_fast;
      const VertexEnergy<double> e_ad = vertex_energy_derivatives(c.q, c.s, g_ad, h_ad);
      const VertexEnergy<double> e_fast = vertex_energy_hessian(c.q, c.s, g_fast, h_fast);
      const VertexEnergy<double> e_only = vertex_energy_gradient(c.q, c.s, g_only);
      const VertexEnergy<double> e_plain = vertex_energy(c.q, c.s);
      const double escale = std::abs(e_ad.bending) + std::abs(e_ad.twisting);
      CHECK(std::abs(e_fast.bending - e_ad.bending) <= 1e-13 * escale);
      CHECK(std::abs(e_fast.twisting - e_ad.twisting) <= 1e-13 * escale);
      CHECK(std::abs(e_only.bending - e_plain.bending) <= 1e-13 * escale);
      CHECK(std::abs(e_only.twisting - e_plain.twisting) <= 1e-13 * escale);
      const double gscale = g_ad.cwiseAbs().maxCoeff(), hscale = h_ad.cwiseAbs().maxCoeff();
      REQUIRE(gscale > 0.0);
      REQUIRE(hscale > 0.0);
      CHECK((g_fast - g_ad).cwiseAbs().maxCoeff() <= 1e-12 * gscale);
      CHECK((g_only - g_ad).cwiseAbs().maxCoeff() <= 1e-12 * gscale);
      CHECK((h_fast - h_ad).cwiseAbs().maxCoeff() <= 1e-11 * hscale);
      CHECK((h_fast - h_fast.transpose()).cwiseAbs().maxCoeff() == 0.0);
      compared += 2 * 11 + 121;
      ++stencils;
    }
  }
  CHECK(stencils == 120);
  CHECK(compared == 120 * (2 * 11 + 121));
}

TEST_CASE(
    "Rod gradient and Hessian from the fast kernels: one pass equals the separate paths, pattern "
    "holds") {
  std::mt19937 rng(5);
  int checked = 0;
  for (int trial = 0; trial < 4; ++trial) {
    ElasticRod rod = random_curved_rod(7, rng, anisotropic_stiffness());
    perturb(rod, rng, 0.2);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(rod.num_dofs());
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(rod.num_dofs(), rod.num_dofs());
    rod.add_gradient_and_hessian(g, h);
    const Eigen::VectorXd g_plain = rod.gradient();
    const Eigen::MatrixXd h_sparse(rod.hessian());
    CHECK((g - g_plain).cwiseAbs().maxCoeff() <= 1e-13 * g.cwiseAbs().maxCoeff());
    CHECK((h - h_sparse).cwiseAbs().maxCoeff() <= 1e-13 * h.cwiseAbs().maxCoeff());
    const auto pattern = rod.hessian_pattern();
    int outside = 0, inside = 0;
    for (int c = 0; c < rod.num_dofs(); ++c)
      for (int r = 0; r < rod.num_dofs(); ++r) {
        if (pattern(r, c))
          ++inside;
        else if (h(r, c) != 0.0)
          ++outside;
      }
    CHECK(outside == 0);
    CHECK(inside < rod.num_dofs() * rod.num_dofs());
    checked += rod.num_dofs() * rod.num_dofs();
  }
  CHECK(checked == 4 * (3 * 8 + 7) * (3 * 8 + 7));
}

}  // namespace xshell::test
