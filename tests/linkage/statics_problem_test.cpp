#include "linkage/statics_problem.hpp"

#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "linkage/model_error.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {
StaticsSetup loaded_setup() {
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0.3, 0.1, -9.0);
  setup.forces = {{0, Eigen::Vector3d(0.1, 0.0, -0.3)}, {1, Eigen::Vector3d(0.0, 0.2, 0.1)}};
  return setup;
}
}  // namespace

TEST_CASE("Problem gradient and Hessian with gravity and point loads match finite differences") {
  std::mt19937 rng(3);
  int checked = 0;
  for (const LineGraph& g : {single_x(), grid(3, 3, 0.3)}) {
    LinkageProblem problem(RodLinkage(g, test_options(RestShape::Straight)), loaded_setup());
    problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.03));
    problem.rebase();
    const Eigen::VectorXd q = problem.free_dofs();
    const auto f = [&](const Eigen::VectorXd& y) {
      LinkageProblem copy = problem;
      copy.set_free_dofs(y);
      return copy.energy().total();
    };
    const auto grad = [&](const Eigen::VectorXd& y) {
      LinkageProblem copy = problem;
      copy.set_free_dofs(y);
      return copy.free_gradient();
    };
    const auto rg = check_gradient(f, q, problem.free_gradient(), 1e-6);
    const auto rh = check_hessian(grad, q, Eigen::MatrixXd(problem.free_hessian()), 1e-6);
    CHECK(rg.relative_error() < 1e-6);
    CHECK(rh.relative_error() < 1e-5);
    CHECK(problem.energy().external != 0.0);
    checked += rg.compared + rh.compared;
  }
  CHECK(checked > 1000);
}

TEST_CASE(
    "Setting the unknowns with the energy in one pass gives energy() bit for bit, loads included") {
  std::mt19937 rng(41);
  // 40 segments: above the size at which segments are set in parallel.
  LinkageProblem problem(RodLinkage(grid(5, 5, 0.3), test_options(RestShape::Straight)),
                         loaded_setup());
  REQUIRE(problem.linkage().num_segments() >= 32);
  const Eigen::VectorXd start = problem.free_dofs();
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = start + random_vector(problem.num_free(), rng, 0.03);
    const double fused = problem.set_free_dofs_and_energy(q);
    const Eigen::VectorXd r_fused = problem.dofs();
    problem.set_free_dofs(q);
    CHECK(problem.dofs() == r_fused);
    CHECK(fused == problem.energy().total());
    CHECK(problem.energy().external != 0.0);
  }
}

TEST_CASE("Without supports the joint nearest the centre is pinned, supports are checked") {
  const LinkageProblem pinned(RodLinkage(grid(3, 3), test_options()), StaticsSetup{});
  CHECK(pinned.default_support_vertex() == 4);
  CHECK(pinned.num_free() == pinned.linkage().num_dofs() - 6);

  StaticsSetup bad;
  bad.supports = {{17, {SupportDof::Position}}};
  CHECK_THROWS_WITH_AS(LinkageProblem(RodLinkage(grid(3, 3), test_options()), bad),
                       doctest::Contains("vertex 17"), ModelError);
  StaticsSetup free_end_angle;
  free_end_angle.supports = {{1, {SupportDof::OpeningAngle}}};
  CHECK_THROWS_WITH_AS(LinkageProblem(RodLinkage(single_x(), test_options()), free_end_angle),
                       doctest::Contains("free rod end has no opening angle"), ModelError);
  StaticsSetup clamp;
  clamp.supports = {{1, {SupportDof::Orientation}}, {2, {SupportDof::X}}};
  LinkageOptions clamp_options = test_options();
  clamp_options.clamped_ends = clamped_free_ends(single_x(), clamp.supports);
  CHECK(clamp_options.clamped_ends == std::vector<int>{1});
  const LinkageProblem clamped(RodLinkage(single_x(), clamp_options), clamp);
  CHECK(clamped.default_support_vertex() == -1);
  CHECK(clamped.num_free() == clamped.linkage().num_dofs() - 7 - 1);
}

TEST_CASE("A rebase carries the velocity over: the motion it describes is unchanged") {
  std::mt19937 rng(12);
  LinkageProblem problem(RodLinkage(grid(3, 3, 0.3), test_options(RestShape::Straight)),
                         StaticsSetup{});
  problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05));
  problem.rebase();
  // Move away from the rebased state so that omega != 0 and the frames are
  // transported.
  problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05));
  const Eigen::VectorXd v = random_vector(problem.num_free(), rng, 1.0);

  // Material frames and nodes after moving by h along a velocity.
  auto state_after = [](LinkageProblem p, const Eigen::VectorXd& velocity, double h) {
    p.set_free_dofs(p.free_dofs() + h * velocity);
    std::vector<double> out;
    for (int s = 0; s < p.linkage().num_segments(); ++s) {
      const ElasticRod& rod = p.linkage().segment(s);
      for (const auto& x : rod.nodes()) out.insert(out.end(), {x.x(), x.y(), x.z()});
      for (int j = 0; j < rod.num_edges(); ++j) {
        const Eigen::Vector3d d1 = rod.material_frame(j).d1.values();
        out.insert(out.end(), {d1.x(), d1.y(), d1.z()});
      }
    }
    return Eigen::Map<Eigen::VectorXd>(out.data(), static_cast<Eigen::Index>(out.size())).eval();
  };
  LinkageProblem rebased = problem;
  Eigen::VectorXd v_new = v;
  rebased.rebase(&v_new);
  CHECK((v_new - v).norm() > 1e-3);  // the transformation did something
  // The two descriptions differ only at second order in h (the error falls
  // fourfold when h halves), whereas the untransformed velocity is already
  // wrong at first order.
  const double h = 1e-3;
  const Eigen::VectorXd a = state_after(problem, v, h);
  const double error = (a - state_after(rebased, v_new, h)).cwiseAbs().maxCoeff();
  const double half = (state_after(problem, v, 0.5 * h) - state_after(rebased, v_new, 0.5 * h))
                          .cwiseAbs()
                          .maxCoeff();
  const double untransformed = (a - state_after(rebased, v, h)).cwiseAbs().maxCoeff();
  CHECK(error / half == doctest::Approx(4.0).epsilon(0.05));
  CHECK(untransformed > 100.0 * error);
  // A plain rebase moves nothing.
  LinkageProblem plain = problem;
  const double e = plain.energy().total();
  plain.rebase();
  CHECK(plain.energy().total() == doctest::Approx(e).epsilon(1e-12));
}

}  // namespace xshell::test
