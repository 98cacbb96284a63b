// The closed-form derivatives (docs/model.md section 7.4) of a terminal edge's theta with respect
// to the edge vectors (edge_vector_theta.hpp) against the exact AD
// derivatives of an edge-vector joint (Joint::terminal_edge_derivatives) and
// against finite differences, at random configurations.
#include "linkage/edge_vector_theta.hpp"

#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "linkage/edge_vector_conversion.hpp"

namespace xshell::test::edge_vector_theta_test {

namespace {

Eigen::Vector3d random_unit(std::mt19937& rng) { return random_vector(3, rng).normalized(); }

// A random edge-vector joint (bases not aligned with its edges) and one of
// its terminal edges with a source frame at `offset` from its tangent
// (0: right after a source-frame update).
struct Case {
  Joint joint;
  EdgeVectorThetaStencil stencil;
};

Case random_case(std::mt19937& rng, int label, int sign, double offset) {
  Eigen::Vector3d e_a, e_b;
  do {
    e_a = random_vector(3, rng) * 1.5;
    e_b = random_vector(3, rng) * 1.5;
  } while (e_a.cross(e_b).norm() < 0.2 * e_a.norm() * e_b.norm() || e_a.norm() < 0.3 ||
           e_b.norm() < 0.3);
  Joint joint = joint_from_edge_vectors({random_vector(3, rng), e_a, e_b}, JointKind::EdgeVectors);
  // Tilt the stored bases: the parameters are then no longer (l, 0, 0).
  const Eigen::Matrix3d tilt = rotation_matrix(random_vector(3, rng, 0.5));
  joint.set_reference_frame(tilt * joint.reference_frame());
  JointParams q = joint.params();
  q.segment<3>(kEdgeA) = joint.edge_basis(0).transpose() * e_a;
  q.segment<3>(kEdgeB) = joint.edge_basis(1).transpose() * e_b;
  joint.set_params(q);

  const Eigen::Vector3d t = sign * (label == 0 ? e_a : e_b).normalized();
  const Eigen::Vector3d t_hat = (t + offset * random_unit(rng)).normalized();
  const Eigen::Vector3d d1_hat = random_unit(rng).cross(t_hat).normalized();
  return {joint, {e_a, e_b, label, sign, {t_hat, d1_hat}}};
}

// 6 x 9 map from the joint's parameters to (e_A, e_B) derivatives: d/de =
// T d/dq restricted to the edge components, T = blockdiag(B_A, B_B).
Eigen::Matrix<double, 6, 6> basis_transform(const Joint& joint) {
  Eigen::Matrix<double, 6, 6> t = Eigen::Matrix<double, 6, 6>::Zero();
  t.block<3, 3>(0, 0) = joint.edge_basis(0);
  t.block<3, 3>(3, 3) = joint.edge_basis(1);
  return t;
}

struct AdTheta {
  Eigen::Matrix<double, 6, 1> gradient;
  Eigen::Matrix<double, 6, 6> hessian;
};

AdTheta ad_theta(const Case& c) {
  Eigen::Matrix<double, 7, 9> jac;
  JointHessian hess[7];
  const double hint =
      c.joint.terminal_edge(c.stencil.label, c.stencil.sign, c.stencil.source, 0.0).theta;
  c.joint.terminal_edge_derivatives(c.stencil.label, c.stencil.sign, c.stencil.source, hint, jac,
                                    hess);
  const Eigen::Matrix<double, 6, 6> t = basis_transform(c.joint);
  return {t * jac.block<1, 6>(6, 3).transpose(), t * hess[6].block<6, 6>(3, 3) * t.transpose()};
}

// Theta as a function of the global edge vectors (e_A, e_B).
double theta_of(const Case& c, const Eigen::VectorXd& e) {
  Joint joint = c.joint;
  JointParams q = joint.params();
  q.segment<3>(kEdgeA) = joint.edge_basis(0).transpose() * e.head<3>();
  q.segment<3>(kEdgeB) = joint.edge_basis(1).transpose() * e.tail<3>();
  joint.set_params(q);
  const double hint =
      c.joint.terminal_edge(c.stencil.label, c.stencil.sign, c.stencil.source, 0.0).theta;
  return joint.terminal_edge(c.stencil.label, c.stencil.sign, c.stencil.source, hint).theta;
}

// Relative error of the seed note's section 4.1 read literally (docs/model.md section 10.1): the
// material d1 = n x t and d2 = n in the first two terms of the transport term g.
double literal_error(const EdgeVectorThetaStencil& s, const Eigen::Matrix<double, 6, 1>& exact) {
  const Eigen::Vector3d& e = s.label == 0 ? s.e_a : s.e_b;
  const Eigen::Vector3d t = s.sign * e.normalized(), n = s.e_a.cross(s.e_b).normalized();
  const Eigen::Vector3d d1 = n.cross(t), d2 = n;
  const Eigen::Vector3d &t_hat = s.source.tangent, &d1_hat = s.source.d1;
  const Eigen::Vector3d d1_ref = reference_frame<double>(V3<double>(t), s.source).d1.values();
  const double chi = 1.0 + t_hat.dot(t);
  const Eigen::Vector3d g = (d1_hat.dot(t) * d1.cross(t_hat) + d2.dot(t_hat) * d1_hat) / chi -
                            d1_hat.dot(t) * d2.dot(t_hat) / (chi * chi) * t_hat +
                            d1_hat.cross(d1_ref);
  const Eigen::Vector3d t_x = e.normalized();
  Eigen::Matrix<double, 6, 1> literal = edge_vector_theta_gradient(s);
  literal.segment<3>(3 * s.label) += s.sign *
                                     (Eigen::Matrix3d::Identity() - t_x * t_x.transpose()) /
                                     e.norm() * (g - transport_turn_gradient(t, s.source));
  return (literal - exact).norm() / exact.norm();
}

Eigen::VectorXd stacked(const EdgeVectorThetaStencil& s) {
  Eigen::VectorXd e(6);
  e << s.e_a, s.e_b;
  return e;
}

}  // namespace

TEST_CASE("Closed-form theta gradient (model 7.4): matches AD and finite differences anywhere") {
  std::mt19937 rng(11);
  int compared = 0, cases = 0;
  double worst_literal = 0.0;
  for (int trial = 0; trial < 24; ++trial)
    for (double offset : {0.0, 0.4}) {
      const Case c = random_case(rng, trial % 2, (trial / 2) % 2 ? -1 : 1, offset);
      CAPTURE(trial);
      CAPTURE(offset);
      const Eigen::Matrix<double, 6, 1> closed_form = edge_vector_theta_gradient(c.stencil);
      const AdTheta ad = ad_theta(c);
      REQUIRE(ad.gradient.norm() > 0.0);
      CHECK((closed_form - ad.gradient).norm() <= 1e-12 * ad.gradient.norm());
      const DifferenceReport fd =
          check_gradient([&](const Eigen::VectorXd& e) { return theta_of(c, e); },
                         stacked(c.stencil), closed_form, 1e-6);
      CHECK(fd.relative_error() < 1e-7);
      // Right after an update the transport term vanishes.
      if (offset == 0.0)
        CHECK(transport_turn_gradient(c.stencil.source.tangent, c.stencil.source).norm() < 1e-14);
      if (offset > 0.0)
        worst_literal = std::max(worst_literal, literal_error(c.stencil, ad.gradient));
      compared += fd.compared + 6;
      ++cases;
    }
  CHECK(cases == 48);
  CHECK(compared == 48 * 12);
  // Read literally (material d1, d2 in the transport term), 4.1 is wrong.
  CHECK(worst_literal > 1e-2);
}

TEST_CASE(
    "Closed-form theta Hessian (model 7.4): matches AD and finite differences after an update") {
  std::mt19937 rng(12);
  int compared = 0;
  double worst_transposed = 0.0, scale = 0.0;
  for (int trial = 0; trial < 24; ++trial) {
    const Case c = random_case(rng, trial % 2, (trial / 2) % 2 ? -1 : 1, 0.0);
    CAPTURE(trial);
    const EdgeVectorThetaHessian closed_form = edge_vector_theta_hessian(c.stencil);
    const Eigen::Matrix<double, 6, 6> h = closed_form.full();
    const AdTheta ad = ad_theta(c);
    const double tol = 1e-12 * ad.hessian.norm();
    CHECK((closed_form.aa - ad.hessian.block<3, 3>(0, 0)).norm() <= tol);
    CHECK((closed_form.bb - ad.hessian.block<3, 3>(3, 3)).norm() <= tol);
    CHECK((closed_form.ab - ad.hessian.block<3, 3>(0, 3)).norm() <= tol);  // rows e_A, columns e_B
    CHECK((closed_form.aa - closed_form.aa.transpose()).norm() <= tol);
    CHECK((closed_form.bb - closed_form.bb.transpose()).norm() <= tol);
    // Finite differences of the (everywhere valid) closed-form gradient.
    const DifferenceReport fd = check_hessian(
        [&](const Eigen::VectorXd& e) {
          EdgeVectorThetaStencil s = c.stencil;
          s.e_a = e.head<3>();
          s.e_b = e.tail<3>();
          return Eigen::VectorXd(edge_vector_theta_gradient(s));
        },
        stacked(c.stencil), h, 1e-6);
    CHECK(fd.relative_error() < 1e-7);
    worst_transposed = std::max(worst_transposed,
                                (closed_form.ab.transpose() - ad.hessian.block<3, 3>(0, 3)).norm());
    scale = std::max(scale, ad.hessian.norm());
    compared += fd.compared + 3 * 9;
  }
  CHECK(compared == 24 * (36 + 27));
  // The other orientation of the cross block would be wrong.
  CHECK(worst_transposed > 1e-2 * scale);
}

TEST_CASE(
    "Closed-form theta Hessian (model 7.4) holds only at the update: away from it the exact "
    "Hessian differs") {
  std::mt19937 rng(13);
  int cases = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const Case c = random_case(rng, trial % 2, 1, 0.5);
    const AdTheta ad = ad_theta(c);
    const Eigen::Matrix<double, 6, 6> closed_form = edge_vector_theta_hessian(c.stencil).full();
    CHECK((closed_form - ad.hessian).norm() > 1e-6 * ad.hessian.norm());
    ++cases;
  }
  CHECK(cases == 8);
}

}  // namespace xshell::test::edge_vector_theta_test
