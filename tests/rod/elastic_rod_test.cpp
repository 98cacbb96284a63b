#include <doctest/doctest.h>

#include "rod/stretching.hpp"
#include "rod_fixtures.hpp"

namespace xshell::test {

namespace {
// Energy, gradient and Hessian of a copy of `rod` moved to q (the source
// frames stay as they are in `rod`).
double energy_at(const ElasticRod& rod, const Eigen::VectorXd& q) {
  ElasticRod r = rod;
  r.set_dofs(q);
  return r.energy().total();
}
Eigen::VectorXd gradient_at(const ElasticRod& rod, const Eigen::VectorXd& q) {
  ElasticRod r = rod;
  r.set_dofs(q);
  return r.gradient();
}

struct TermCase {
  const char* name;
  double stretch, bend, twist;  // multipliers of EA, B1 and B2, GJ
};

int check_rod_derivatives(const ElasticRod& rod, double gradient_tol, double hessian_tol) {
  const Eigen::VectorXd q = rod.dofs();
  const auto f = [&](const Eigen::VectorXd& y) { return energy_at(rod, y); };
  const auto g = [&](const Eigen::VectorXd& y) { return gradient_at(rod, y); };
  const Eigen::VectorXd grad = rod.gradient();
  const Eigen::MatrixXd hess = Eigen::MatrixXd(rod.hessian());
  CHECK((hess - hess.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * hess.cwiseAbs().maxCoeff());
  const DifferenceReport rg = check_gradient(f, q, grad, 1e-6);
  const DifferenceReport rh = check_hessian(g, q, hess, 1e-6);
  CHECK(rg.scale > 0.0);
  CHECK(rh.scale > 0.0);
  CHECK(rg.relative_error() < gradient_tol);
  CHECK(rh.relative_error() < hessian_tol);
  return rg.compared + rh.compared;
}
}  // namespace

TEST_CASE("Rod gradient and Hessian of every term match finite differences") {
  const TermCase terms[] = {
      {"stretching", 1, 0, 0}, {"bending", 0, 1, 0}, {"twisting", 0, 0, 1}, {"all", 1, 1, 1}};
  std::mt19937 rng(2024);
  int checked = 0;
  for (const TermCase& term : terms) {
    CAPTURE(term.name);
    RodStiffness k = anisotropic_stiffness();
    k.stretching *= term.stretch;
    k.bending1 *= term.bend;
    k.bending2 *= term.bend;
    k.twisting *= term.twist;
    for (int trial = 0; trial < 3; ++trial) {
      ElasticRod rod = random_curved_rod(6, rng, k);
      rod.set_stretching_share(0, 0.5);
      perturb(rod, rng, 0.15);
      // Right after a source-frame update...
      rod.update_source_frames();
      checked += check_rod_derivatives(rod, 1e-7, 1e-6);
      // ...and away from it: the finite-transport formulation is exact there too.
      perturb(rod, rng, 0.15);
      checked += check_rod_derivatives(rod, 1e-7, 1e-6);
    }
  }
  const int dofs = 3 * 7 + 6;
  CHECK(checked == 4 * 3 * 2 * (dofs + dofs * dofs));
}

TEST_CASE("Updating the source frames changes neither configuration nor energy") {
  std::mt19937 rng(5);
  ElasticRod rod = random_curved_rod(8, rng, anisotropic_stiffness());
  perturb(rod, rng, 0.2);
  const RodEnergy before = rod.energy();
  const Eigen::VectorXd q = rod.dofs();
  std::vector<Eigen::Vector3d> d2_before;
  for (int j = 0; j < rod.num_edges(); ++j) d2_before.push_back(rod.material_frame(j).d2.values());
  rod.update_source_frames();
  CHECK(before.total() > 0.0);
  CHECK(rod.energy().total() == doctest::Approx(before.total()).epsilon(1e-12));
  CHECK(rod.energy().twisting == doctest::Approx(before.twisting).epsilon(1e-12));
  CHECK((rod.dofs() - q).norm() == 0.0);
  for (int j = 0; j < rod.num_edges(); ++j)
    CHECK((rod.material_frame(j).d2.values() - d2_before[j]).norm() < 1e-13);
}

TEST_CASE("Rod energy is invariant under rigid motions, its gradient is orthogonal to them") {
  std::mt19937 rng(9);
  ElasticRod rod = random_curved_rod(7, rng, anisotropic_stiffness());
  perturb(rod, rng, 0.2);
  rod.update_source_frames();
  const Eigen::VectorXd g = rod.gradient();
  REQUIRE(rod.energy().total() > 0.0);
  // Infinitesimal rigid motions in (x, theta): a translation moves the nodes;
  // a rotation w moves node x by w x x and, since the reference frame is
  // transported without twist, each theta_j by w . t_j so that the material
  // frame turns rigidly with the nodes.
  double worst = 0.0;
  int motions = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d w = Eigen::Vector3d::Unit(axis);
    Eigen::VectorXd translation = Eigen::VectorXd::Zero(rod.num_dofs());
    Eigen::VectorXd rotation = Eigen::VectorXd::Zero(rod.num_dofs());
    for (int k = 0; k < rod.num_nodes(); ++k) {
      translation[3 * k + axis] = 1.0;
      rotation.segment<3>(3 * k) = w.cross(rod.nodes()[k]);
    }
    for (int j = 0; j < rod.num_edges(); ++j) rotation[rod.theta_dof(j)] = w.dot(rod.tangent(j));
    worst = std::max({worst, std::abs(g.dot(translation)) / (g.norm() * translation.norm()),
                      std::abs(g.dot(rotation)) / (g.norm() * rotation.norm())});
    motions += 2;
  }
  CHECK(motions == 6);
  CHECK(worst < 1e-10);

  // A finite rigid motion of the nodes and source frames together, from the
  // same rest state, leaves the energy unchanged.
  const Eigen::Matrix3d r = rotation_matrix(Eigen::Vector3d(0.7, -0.4, 1.1));
  const Eigen::Vector3d shift(3.0, -2.0, 0.5);
  ElasticRod original = random_curved_rod(7, rng, anisotropic_stiffness());
  std::vector<Eigen::Vector3d> rest_nodes = original.nodes();
  std::vector<SourceFrame> frames = original.source_frames();
  for (auto& x : rest_nodes) x = r * x + shift;
  for (auto& f : frames) {
    f.tangent = r * f.tangent;
    f.d1 = r * f.d1;
  }
  ElasticRod moved(rest_nodes, frames, original.thetas(), original.stiffness());
  perturb(original, rng, 0.2);
  std::vector<Eigen::Vector3d> deformed = original.nodes();
  for (auto& x : deformed) x = r * x + shift;
  moved.set_configuration(deformed, original.thetas());
  CHECK(original.energy().total() > 0.0);
  CHECK(moved.energy().total() == doctest::Approx(original.energy().total()).epsilon(1e-11));
  CHECK(moved.energy().twisting == doctest::Approx(original.energy().twisting).epsilon(1e-11));
}

TEST_CASE("A straight rod at rest has zero energy and zero gradient") {
  std::vector<Eigen::Vector3d> nodes;
  for (int i = 0; i <= 6; ++i) nodes.emplace_back(0.3 * i, 0.1 * i, -0.2 * i);
  ElasticRod rod(nodes, anisotropic_stiffness());
  // Strains vanish up to round-off (fused multiply-adds leave ~1e-17 in
  // e0 x e1); the energy is quadratic in them.
  CHECK(rod.energy().total() < 1e-30);
  CHECK(rod.gradient().cwiseAbs().maxCoeff() < 1e-14);
}

TEST_CASE("Three nodes with turning angle phi: |kb| = 2 tan(phi/2) and E_bend = 2 B tan^2(phi/2)") {
  RodStiffness k;
  k.stretching = 1.0;
  k.bending1 = k.bending2 = 3.0;
  k.twisting = 1.0;
  int checked = 0;
  for (double phi : {0.1, 0.7, 1.5, 2.5}) {
    const std::vector<Eigen::Vector3d> straight = {{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}};
    ElasticRod rod(straight, k);  // straight at rest, unit edges, V = 1
    const std::vector<Eigen::Vector3d> bent = {
        {-1, 0, 0}, {0, 0, 0}, {std::cos(phi), std::sin(phi), 0}};
    rod.set_configuration(bent, rod.thetas());
    const VertexStrains<double> s = rod.strains(1);
    CHECK(norm(s.kb) == doctest::Approx(2.0 * std::tan(0.5 * phi)).epsilon(1e-13));
    const double t = std::tan(0.5 * phi);
    CHECK(rod.energy().bending == doctest::Approx(2.0 * 3.0 * t * t).epsilon(1e-13));
    CHECK(rod.energy().stretching == doctest::Approx(0.0));
    ++checked;
  }
  CHECK(checked == 4);
}

TEST_CASE("Stretching of one edge: value and known derivatives") {
  const Eigen::Vector3d e(1.5, 0.0, 0.0);
  CHECK(stretching_energy(e, 1.0, 4.0) == doctest::Approx(0.5 * 4.0 * 0.25));
  CHECK(stretching_gradient(e, 1.0, 4.0).x() == doctest::Approx(2.0));
  const Eigen::Matrix3d h = stretching_hessian(e, 1.0, 4.0);
  CHECK(h(0, 0) == doctest::Approx(4.0));
  CHECK(h(1, 1) == doctest::Approx(4.0 * 0.5 / 1.5));
}

}  // namespace xshell::test
