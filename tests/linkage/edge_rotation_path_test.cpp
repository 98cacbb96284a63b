// The edge-turning path of the Newton line searches (edge_rotation_path.hpp,
// docs/model.md section 9.8): it leaves q0 with tangent p, moves only free
// node and joint positions, and turns a run of edges rigidly without
// stretching it.
#include "linkage/edge_rotation_path.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "linkage/statics_problem.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {

Eigen::VectorXd random_vector(Eigen::Index n, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

// Per free unknown: true when it is a coordinate of a segment's node or of
// a joint's position.
std::vector<bool> position_coordinates(const LinkageProblem& problem) {
  const RodLinkage& linkage = problem.linkage();
  std::vector<bool> is_node(linkage.num_dofs(), false);
  for (int s = 0; s < linkage.num_segments(); ++s)
    for (int k = 0; k < 3 * linkage.segment(s).num_nodes(); ++k) {
      const int r = linkage.reduced_index(s, k);
      if (r >= 0) is_node[r] = true;
    }
  for (int j = 0; j < linkage.num_joints(); ++j)
    for (int c = 0; c < 3; ++c) is_node[linkage.joint_dof_offset(j) + c] = true;
  std::vector<bool> free_is_node;
  for (int r : problem.free_indices()) free_is_node.push_back(is_node[r]);
  return free_is_node;
}

// The free unknowns of the joints' positions.
std::vector<int> joint_positions(const LinkageProblem& problem) {
  std::vector<int> out;
  for (int j = 0; j < problem.linkage().num_joints(); ++j)
    for (int c = 0; c < 3; ++c) {
      const int k = problem.free_position(problem.linkage().joint_dof_offset(j) + c);
      if (k >= 0) out.push_back(k);
    }
  return out;
}

// The largest deviation of the joints' positions from the straight step.
double joint_deviation(LinkageProblem& problem, const EdgeRotationPath& path,
                       const Eigen::VectorXd& q0, const Eigen::VectorXd& p, double alpha) {
  const Eigen::VectorXd deviation = path.point(problem, alpha) - (q0 + alpha * p);
  double largest = 0.0;
  for (int k : joint_positions(problem)) largest = std::max(largest, std::abs(deviation[k]));
  return largest;
}

}  // namespace

TEST_CASE("The edge-turning path leaves q0 with tangent p and moves only positions") {
  LinkageProblem problem(RodLinkage(grid(3, 3, 0.3), test_options(RestShape::Input, 6)), {});
  const Eigen::VectorXd q0 = problem.free_dofs();
  const Eigen::VectorXd p = random_vector(q0.size(), 0.05, 7);
  EdgeRotationPath path(problem);
  path.start(problem, p, true);
  const std::vector<bool> is_node = position_coordinates(problem);

  CHECK((path.point(problem, 0.0) - q0).lpNorm<Eigen::Infinity>() < 1e-14);
  double previous = 0.0;
  int halvings = 0;
  for (double alpha : {0.4, 0.2, 0.1, 0.05}) {
    CAPTURE(alpha);
    const Eigen::VectorXd deviation = path.point(problem, alpha) - (q0 + alpha * p);
    double off_nodes = 0.0;
    for (Eigen::Index i = 0; i < q0.size(); ++i)
      if (!is_node[i]) off_nodes = std::max(off_nodes, std::abs(deviation[i]));
    CHECK(off_nodes == 0.0);  // joint rotations and angles, thetas: the straight step
    const double d = deviation.lpNorm<Eigen::Infinity>();
    CHECK(d > 1e-8);  // the path is curved
    if (previous > 0.0) {
      // Second order in alpha: the deviation falls 4 times per halving.
      CHECK(previous / d == doctest::Approx(4.0).epsilon(0.1));
      ++halvings;
    }
    previous = d;
  }
  CHECK(halvings == 3);
  // The points were computed without moving the problem.
  CHECK(problem.free_dofs() == q0);
}

TEST_CASE("The joints turn only on a Newton step and only up to the full step") {
  LinkageProblem problem(RodLinkage(grid(3, 3, 0.3), test_options(RestShape::Input, 6)), {});
  const Eigen::VectorXd q0 = problem.free_dofs();
  const Eigen::VectorXd p = random_vector(q0.size(), 0.05, 11);
  REQUIRE(joint_positions(problem).size() >= 6);
  EdgeRotationPath path(problem);
  path.start(problem, p, true);
  CHECK(joint_deviation(problem, path, q0, p, 0.5) > 1e-8);
  CHECK(joint_deviation(problem, path, q0, p, 1.0) > 1e-8);
  CHECK(joint_deviation(problem, path, q0, p, 2.0) == 0.0);
  problem.set_free_dofs(q0);
  path.start(problem, p, false);
  CHECK(joint_deviation(problem, path, q0, p, 0.5) == 0.0);
}

TEST_CASE("Along the edge-turning path a cantilever's free part turns rigidly, unstretched") {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}};
  g.edges = {{0, 1}};
  LinkageOptions o = test_options(RestShape::Straight, 20);
  StaticsSetup setup;
  setup.supports = {{0, {SupportDof::Position, SupportDof::Orientation}}};
  o.clamped_ends = clamped_free_ends(g, setup.supports);
  LinkageProblem problem(RodLinkage(g, o), setup);
  const RodLinkage& linkage = problem.linkage();
  const std::vector<Eigen::Vector3d> start = linkage.segment(0).nodes();
  const int n = static_cast<int>(start.size());
  std::vector<int> free_of(linkage.num_dofs(), -1);
  for (int k = 0; k < problem.num_free(); ++k) free_of[problem.free_indices()[k]] = k;

  // p: the linearized turn about y through node 1 (the clamp holds nodes 0
  // and 1) of every free node; thetas unchanged.
  const Eigen::Vector3d w = Eigen::Vector3d::UnitY();
  Eigen::VectorXd p = Eigen::VectorXd::Zero(problem.num_free());
  int moved = 0;
  for (int i = 0; i < n; ++i) {
    const int x = linkage.reduced_index(0, 3 * i);
    if (x < 0 || free_of[x] < 0) continue;
    const Eigen::Vector3d v = w.cross(start[i] - start[1]);
    for (int c = 0; c < 3; ++c) p[free_of[linkage.reduced_index(0, 3 * i + c)]] = v[c];
    ++moved;
  }
  REQUIRE(moved == n - 2);

  EdgeRotationPath path(problem);
  path.start(problem, p);
  const Eigen::VectorXd q0 = problem.free_dofs();
  for (double alpha : {0.3, 1.0}) {
    CAPTURE(alpha);
    problem.set_free_dofs(path.point(problem, alpha));
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(alpha, w).toRotationMatrix();
    double error = 0.0;
    for (int i = 2; i < n; ++i)  // the free nodes
      error = std::max(error,
                       (linkage.segment(0).nodes()[i] - (start[1] + turn * (start[i] - start[1])))
                           .lpNorm<Eigen::Infinity>());
    CHECK(error < 1e-12);
    const double turned = problem.energy().stretching;
    problem.set_free_dofs(q0 + alpha * p);
    const double straight = problem.energy().stretching;
    CHECK(turned < 1e-20 * straight + 1e-24);
    CHECK(straight > 0.0);
  }
}

}  // namespace xshell::test

namespace xshell::test {

// The joint turns its terminal nodes on arcs; the free edge next to them
// turns by its own linearized step, not by the difference between an arc
// and a line (docs/model.md section 9.8).
TEST_CASE("Along the edge-turning path a rod swinging about its joint turns rigidly, unstretched") {
  const LineGraph g = single_x();
  LinkageOptions o = test_options(RestShape::Input, 6);
  StaticsSetup setup;
  setup.supports = {{1, {SupportDof::Position, SupportDof::Orientation}}};
  o.clamped_ends = clamped_free_ends(g, setup.supports);
  LinkageProblem problem(RodLinkage(g, o), setup);
  // The mechanism: the second rod turning about the joint's normal, the
  // free Hessian's only null vector at the stress-free start.
  const Eigen::MatrixXd H = problem.free_hessian();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> modes(H);
  REQUIRE(std::abs(modes.eigenvalues()(0)) < 1e-9 * modes.eigenvalues()(1));
  const int alpha = problem.free_position(problem.linkage().joint_dof_offset(0) + kAlpha);
  REQUIRE(alpha >= 0);
  const Eigen::VectorXd q0 = problem.free_dofs();
  std::vector<double> turned;
  for (const double turn : {0.2, 0.6}) {
    CAPTURE(turn);
    const Eigen::VectorXd p = (turn / modes.eigenvectors()(alpha, 0)) * modes.eigenvectors().col(0);
    problem.set_free_dofs(q0 + p);
    const double straight = problem.energy().total();
    problem.set_free_dofs(q0);
    EdgeRotationPath path(problem);
    path.start(problem, p, true);
    problem.set_free_dofs(path.point(problem, 1.0));
    turned.push_back(problem.energy().total());
    problem.set_free_dofs(q0);
    CHECK(straight > 1e-6);
    CHECK(turned.back() < 1e-7 * straight);  // 1e-6 with the joints' arcs against lines
  }
  // What is left is third order in the turn (the thetas' straight step
  // against the frames' transport): the energy grows as its sixth power, not
  // as the fourth of a second-order error.
  CHECK(turned[1] > 0.0);
  CHECK(turned[1] / turned[0] > std::pow(3.0, 5));
  // No point of the path turns the rod by more than a quarter turn: at 2
  // radians per unit alpha, up to alpha = pi / 4.
  const Eigen::VectorXd p = (2.0 / modes.eigenvectors()(alpha, 0)) * modes.eigenvectors().col(0);
  EdgeRotationPath path(problem);
  path.start(problem, p, true);
  CHECK_NOTHROW(path.point(problem, 0.77));
  CHECK_THROWS_AS(path.point(problem, 0.8), std::domain_error);
  problem.set_free_dofs(q0);
}

}  // namespace xshell::test
