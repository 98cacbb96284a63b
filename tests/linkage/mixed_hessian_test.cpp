// Newton's mixed Hessian on a linkage (LinkageProblem::use_mixed_hessian,
// docs/model.md section 9.8): the exact Hessian plus the geometric
// stiffness of the axial forces' change, through the joints' second
// derivatives too.
#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "linkage/statics_problem.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {

struct AxialForces {
  std::vector<Eigen::VectorXd> per_segment;
};

AxialForces axial_forces(const LinkageProblem& problem) {
  AxialForces out;
  const RodLinkage& l = problem.linkage();
  for (int s = 0; s < l.num_segments(); ++s) {
    Eigen::VectorXd n(l.segment(s).num_edges());
    for (int j = 0; j < n.size(); ++j) n[j] = l.segment(s).axial_force(j);
    out.per_segment.push_back(n);
  }
  return out;
}

// F(q) = sum over all edges of c_j |e_j(q)|.
double length_sum(const LinkageProblem& problem, const Eigen::VectorXd& q, const AxialForces& c) {
  LinkageProblem copy = problem;
  copy.set_free_dofs(q);
  double f = 0.0;
  for (int s = 0; s < copy.linkage().num_segments(); ++s)
    for (int j = 0; j < copy.linkage().segment(s).num_edges(); ++j)
      f += c.per_segment[s][j] * copy.linkage().segment(s).edge(j).norm();
  return f;
}

// u^T (Hessian of F) v by central differences.
double second_difference(const LinkageProblem& problem, const Eigen::VectorXd& q,
                         const AxialForces& c, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                         double h) {
  return (length_sum(problem, q + h * (u + v), c) - length_sum(problem, q + h * (u - v), c) -
          length_sum(problem, q - h * (u - v), c) + length_sum(problem, q - h * (u + v), c)) /
         (4.0 * h * h);
}

}  // namespace

TEST_CASE("Mixed linkage Hessian: exact plus the Hessian of sum_j (sigma_j - N_j) |e_j|") {
  std::mt19937 rng(17);
  int checked = 0;
  for (JointKind kind : {JointKind::Rotation, JointKind::EdgeVectors})
    for (const LineGraph& g : {single_x(), grid(3, 3, 0.3)}) {
      LinkageOptions options = test_options(RestShape::Straight);
      options.joint_kind = kind;
      StaticsSetup setup;
      setup.gravity = Eigen::Vector3d(0.3, 0.1, -9.0);
      LinkageProblem problem(RodLinkage(g, options), setup);
      problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.03));
      problem.rebase();
      const Eigen::VectorXd q = problem.free_dofs();
      const Eigen::VectorXd p = random_vector(problem.num_free(), rng, 0.1);
      // sigma = N + dN/dt along q + t p, by central differences.
      const double h = 1e-6;
      LinkageProblem ahead = problem, behind = problem;
      ahead.set_free_dofs(q + h * p);
      behind.set_free_dofs(q - h * p);
      const AxialForces n1 = axial_forces(ahead), n2 = axial_forces(behind);
      AxialForces change;  // sigma - N
      for (size_t s = 0; s < n1.per_segment.size(); ++s)
        change.per_segment.push_back((n1.per_segment[s] - n2.per_segment[s]) / (2.0 * h));

      const Eigen::MatrixXd exact(problem.free_hessian());
      const Eigen::VectorXd gradient = problem.free_gradient();
      problem.use_mixed_hessian(p);
      CHECK(problem.mixed_hessian());
      const Eigen::MatrixXd mixed(problem.free_hessian());
      CHECK(problem.free_gradient() == gradient);
      const Eigen::MatrixXd difference = mixed - exact;
      CHECK(difference.cwiseAbs().maxCoeff() > 1e-6 * exact.cwiseAbs().maxCoeff());
      CHECK((mixed - mixed.transpose()).cwiseAbs().maxCoeff() == 0.0);
      double worst = 0.0, scale = 0.0;
      for (int pair = 0; pair < 6; ++pair) {
        const Eigen::VectorXd u = random_vector(problem.num_free(), rng);
        const Eigen::VectorXd v = random_vector(problem.num_free(), rng);
        const double analytic = u.dot(difference * v);
        const double numeric = second_difference(problem, q, change, u, v, 1e-4);
        worst = std::max(worst, std::abs(analytic - numeric));
        scale = std::max(scale, std::abs(analytic));
        ++checked;
      }
      CAPTURE(worst);
      CAPTURE(scale);
      CHECK(scale > 0.0);
      CHECK(worst <= 1e-5 * scale);

      problem.use_exact_hessian();
      CHECK(!problem.mixed_hessian());
      CHECK((Eigen::MatrixXd(problem.free_hessian()) - exact).cwiseAbs().maxCoeff() == 0.0);
    }
  CHECK(checked == 4 * 6);
}

TEST_CASE("A step that changes no edge by more than 1e-4 of its length keeps the Hessian exact") {
  std::mt19937 rng(5);
  LinkageProblem problem(RodLinkage(grid(3, 3, 0.3), test_options(RestShape::Straight)),
                         StaticsSetup{});
  problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.03));
  problem.rebase();
  const Eigen::MatrixXd exact(problem.free_hessian());
  const Eigen::VectorXd direction = random_vector(problem.num_free(), rng);
  // The largest relative edge change along the direction, as the problem
  // measures it.
  const RodLinkage& l = problem.linkage();
  const Eigen::VectorXd full = problem.with_fixed_zero(direction);
  double change = 0.0;
  for (int s = 0; s < l.num_segments(); ++s)
    change = std::max(change, l.segment(s).largest_edge_change(l.full_velocity(s, full)));
  REQUIRE(change > 0.0);
  const double negligible = LinkageProblem::kNegligibleEdgeChange / change;

  problem.use_mixed_hessian(0.5 * negligible * direction);
  CHECK(!problem.mixed_hessian());
  CHECK((Eigen::MatrixXd(problem.free_hessian()) - exact).cwiseAbs().maxCoeff() == 0.0);
  problem.use_mixed_hessian(2.0 * negligible * direction);
  CHECK(problem.mixed_hessian());
  CHECK((Eigen::MatrixXd(problem.free_hessian()) - exact).cwiseAbs().maxCoeff() > 0.0);
  // And back: a negligible step after a mixed one makes it exact again.
  problem.use_mixed_hessian(0.5 * negligible * direction);
  CHECK(!problem.mixed_hessian());
  CHECK((Eigen::MatrixXd(problem.free_hessian()) - exact).cwiseAbs().maxCoeff() == 0.0);
}

}  // namespace xshell::test
