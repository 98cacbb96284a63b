#include "integrators/deployment/joint_charts.hpp"

#include <doctest/doctest.h>

#include <random>

#include "deployment_fixtures.hpp"

namespace xshell::test {

namespace {

// A curved path through the dome's unknowns: every free unknown moves with
// s and s^2, the omegas by up to a radian, the others by centimetres.
struct CurvedPath {
  Eigen::VectorXd q0, v, w;
  Eigen::VectorXd at(double s) const { return q0 + s * v + s * s * w; }
  Eigen::VectorXd tangent(double s) const { return v + 2.0 * s * w; }
};

CurvedPath curved_path(const LinkageProblem& problem, const std::vector<FreeRotation>& rotations) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  CurvedPath p{problem.free_dofs(), {}, {}};
  p.v = p.q0.unaryExpr([&](double) { return 0.02 * u(rng); });
  p.w = p.q0.unaryExpr([&](double) { return 0.02 * u(rng); });
  for (const FreeRotation& r : rotations)
    for (int i : r.free) {
      p.v[i] = 2.0 * u(rng);
      p.w[i] = 1.0 * u(rng);
    }
  return p;
}

}  // namespace

TEST_CASE(
    "An equilibrium's omegas and their rates, re-expressed after a fold, give the same frames") {
  LinkageProblem problem = dome_problem(3);
  const std::vector<FreeRotation> rotations = free_rotations(problem);
  // The pinned centre joint's omegas are not free; the other eight are.
  REQUIRE(rotations.size() == 8);
  const CurvedPath path = curved_path(problem, rotations);
  const double s0 = 0.1, eps = 1e-5;
  // The point at s0 and its neighbours, in the chart of the start.
  std::vector<PathPoint> points;
  for (double s : {s0, s0 - eps, s0 + eps}) {
    problem.set_free_dofs(path.at(s));
    points.push_back({path.at(s), s, path.tangent(s), joint_frames(problem.linkage(), rotations)});
  }
  const std::vector<Eigen::Matrix3d> frames_at_s0 = points[0].frames;
  // Elsewhere on the path, the charts replaced by a rebase (the omegas folded).
  problem.set_free_dofs(path.at(0.35));
  problem.rebase();
  std::vector<PathPoint> now;
  for (const PathPoint& p : points)
    now.push_back(in_current_charts(p, problem.linkage(), rotations));
  // Its omegas give the frames of s0 in the new charts.
  problem.set_free_dofs(now[0].q);
  const std::vector<Eigen::Matrix3d> again = joint_frames(problem.linkage(), rotations);
  for (size_t i = 0; i < rotations.size(); ++i) {
    CAPTURE(i);
    CHECK((again[i] - frames_at_s0[i]).cwiseAbs().maxCoeff() <= 1e-12);
    // The charts did change: the omega differs from the one recorded.
    Eigen::Vector3d before, after;
    for (int k = 0; k < 3; ++k) {
      before[k] = points[0].q[rotations[i].free[k]];
      after[k] = now[0].q[rotations[i].free[k]];
    }
    CHECK((before - after).norm() > 0.1);
  }
  // Its tangent is the rate of the re-expressed omegas (central
  // difference, error O(eps^2)); the other unknowns are untouched.
  const Eigen::VectorXd rate = (now[2].q - now[1].q) / (2.0 * eps);
  CHECK((rate - now[0].tangent).cwiseAbs().maxCoeff() <= 1e-8);
  for (Eigen::Index i = 0; i < rate.size(); ++i) {
    bool omega = false;
    for (const FreeRotation& r : rotations)
      for (int k : r.free) omega = omega || k == i;
    if (!omega) CHECK(now[0].q[i] == points[0].q[i]);
  }
}

}  // namespace xshell::test
