#include "linkage/rigid_motions.hpp"

#include <doctest/doctest.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <random>

namespace xshell::test {

namespace {

using Dofs = std::vector<SupportDof>;

// Velocity of point x under the motion scaled to unit rate.
Eigen::Vector3d velocity(const RigidMotion& m, const Eigen::Vector3d& x) {
  if (m.kind == RigidMotion::Kind::Translation) return m.direction;
  return m.direction.cross(x - m.point);
}

// Every motion must respect every support: fixed components do not move,
// orientations do not turn. Returns the number of equations checked.
int check_supports_hold(const std::vector<RigidMotion>& motions,
                        const std::vector<VertexSupport>& supports,
                        const std::vector<Eigen::Vector3d>& x) {
  int checked = 0;
  for (const RigidMotion& m : motions) {
    CHECK(m.direction.norm() == doctest::Approx(1.0));
    for (const VertexSupport& s : supports)
      for (SupportDof dof : s.fix) {
        const Eigen::Vector3d v = velocity(m, x[s.vertex]);
        switch (dof) {
          case SupportDof::Position:
            CHECK(v.norm() < 1e-9);
            break;
          case SupportDof::X:
            CHECK(std::abs(v.x()) < 1e-9);
            break;
          case SupportDof::Y:
            CHECK(std::abs(v.y()) < 1e-9);
            break;
          case SupportDof::Z:
            CHECK(std::abs(v.z()) < 1e-9);
            break;
          case SupportDof::Orientation:
            CHECK(m.kind == RigidMotion::Kind::Translation);
            break;
          case SupportDof::OpeningAngle:
            break;
        }
        ++checked;
      }
  }
  return checked;
}

int count(const std::vector<RigidMotion>& motions, RigidMotion::Kind kind) {
  int n = 0;
  for (const RigidMotion& m : motions) n += m.kind == kind;
  return n;
}

// Random, not symmetric, vertex positions.
std::vector<Eigen::Vector3d> random_positions(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2.0, 3.0);
  std::vector<Eigen::Vector3d> x(n);
  for (auto& p : x) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return x;
}

}  // namespace

TEST_CASE(
    "Rigid motions: none held, all six free, position and orientation at one vertex hold all") {
  std::mt19937 rng(7);
  const auto x = random_positions(6, rng);
  const auto all = free_rigid_motions({}, x);
  CHECK(all.size() == 6);
  CHECK(count(all, RigidMotion::Kind::Translation) == 3);
  CHECK(describe(all).rfind(
            "translation along x; translation along y; translation along z; rotation about x", 0) ==
        0);
  CHECK(free_rigid_motions({{2, Dofs{SupportDof::Position, SupportDof::Orientation}}}, x).empty());
  // Orientation alone leaves the three translations.
  const auto turned = free_rigid_motions({{2, Dofs{SupportDof::Orientation}}}, x);
  CHECK(turned.size() == 3);
  CHECK(count(turned, RigidMotion::Kind::Translation) == 3);
  // Opening angles hold nothing; vertices out of range are ignored.
  CHECK(
      free_rigid_motions({{1, Dofs{SupportDof::OpeningAngle}}, {99, Dofs{SupportDof::Position}}}, x)
          .size() == 6);
}

TEST_CASE("Rigid motions: one pin leaves three rotations about axes through it") {
  std::mt19937 rng(11);
  const auto x = random_positions(5, rng);
  const std::vector<VertexSupport> pin = {{3, Dofs{SupportDof::Position}}};
  const auto motions = free_rigid_motions(pin, x);
  REQUIRE(motions.size() == 3);
  CHECK(count(motions, RigidMotion::Kind::Rotation) == 3);
  CHECK(check_supports_hold(motions, pin, x) == 3);
  // Axes x, y, z, in that order, each through the pin.
  for (int axis = 0; axis < 3; ++axis) {
    CHECK((motions[axis].direction - Eigen::Vector3d::Unit(axis)).norm() < 1e-12);
    CHECK(motions[axis].direction.cross(x[3] - motions[axis].point).norm() < 1e-9);
  }
}

TEST_CASE("Rigid motions: two pins leave the rotation about the line through them") {
  std::mt19937 rng(13);
  const auto x = random_positions(4, rng);
  const std::vector<VertexSupport> pins = {{0, Dofs{SupportDof::Position}},
                                           {2, Dofs{SupportDof::Position}}};
  const auto motions = free_rigid_motions(pins, x);
  REQUIRE(motions.size() == 1);
  CHECK(motions[0].kind == RigidMotion::Kind::Rotation);
  CHECK(motions[0].direction.cross((x[2] - x[0]).normalized()).norm() < 1e-9);
  CHECK(check_supports_hold(motions, pins, x) == 2);
  // A third pin off that line holds everything.
  CHECK(free_rigid_motions({pins[0], pins[1], {1, Dofs{SupportDof::Position}}}, x).empty());
}

TEST_CASE(
    "Rigid motions: z rollers under a flat linkage leave it sliding and turning in its plane") {
  std::vector<Eigen::Vector3d> x = {{0, 0, 0.5}, {1.3, 0.2, 0.5}, {0.4, 1.1, 0.5}, {2, 2, 0.5}};
  const std::vector<VertexSupport> rollers = {
      {0, Dofs{SupportDof::Z}}, {1, Dofs{SupportDof::Z}}, {2, Dofs{SupportDof::Z}}};
  const auto motions = free_rigid_motions(rollers, x);
  REQUIRE(motions.size() == 3);
  CHECK(describe(motions).rfind(
            "translation along x; translation along y; rotation about z through (", 0) == 0);
  CHECK(check_supports_hold(motions, rollers, x) == 9);
  // Adding an x and a y roller at two vertices leaves nothing free.
  std::vector<VertexSupport> held = rollers;
  held.push_back({0, Dofs{SupportDof::X, SupportDof::Y}});
  held.push_back({3, Dofs{SupportDof::X}});
  CHECK(free_rigid_motions(held, x).empty());
  // describe() shifts the rotation axis into the user's coordinates.
  const std::vector<RigidMotion> one = {
      {RigidMotion::Kind::Rotation, Eigen::Vector3d(0.6, 0.8, 0), {1, 2, 3}}};
  CHECK(describe(one, Eigen::Vector3d(10, 0, 0)) ==
        "rotation about [0.6, 0.8, 0] through (11, 2, 3)");
}

TEST_CASE(
    "Rigid motions: random supports, every reported motion is free and the count is 6 - rank") {
  std::mt19937 rng(17);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const auto x = random_positions(6, rng);
    std::vector<VertexSupport> supports;
    std::uniform_int_distribution<int> vertex(0, 5), dof(0, 5), how_many(0, 4);
    const int n = how_many(rng);
    for (int i = 0; i < n; ++i)
      supports.push_back({vertex(rng), Dofs{static_cast<SupportDof>(dof(rng))}});
    const auto motions = free_rigid_motions(supports, x);
    checked += check_supports_hold(motions, supports, x);
    // The motions are independent: their velocities at the six vertices
    // (18 numbers each) have full rank.
    Eigen::MatrixXd v(18, static_cast<Eigen::Index>(motions.size()));
    for (std::size_t k = 0; k < motions.size(); ++k)
      for (int i = 0; i < 6; ++i)
        v.block<3, 1>(3 * i, static_cast<Eigen::Index>(k)) = velocity(motions[k], x[i]);
    if (!motions.empty()) {
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(v);
      CHECK(svd.singularValues().minCoeff() > 1e-6);
    }
    // And they are all: 6 - rank of the support equations on (t, w).
    Eigen::MatrixXd equations = Eigen::MatrixXd::Zero(3 * n + 1, 6);
    int row = 0;
    for (const VertexSupport& s : supports)
      for (SupportDof d : s.fix)
        for (int axis = 0; axis < 3; ++axis) {
          const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
          const bool holds = d == SupportDof::Position || static_cast<int>(d) == 1 + axis;
          if (holds) equations.row(row) << e.transpose(), x[s.vertex].cross(e).transpose();
          if (d == SupportDof::Orientation) equations(row, 3 + axis) = 1.0;
          ++row;
        }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(equations);
    lu.setThreshold(1e-9);
    CHECK(static_cast<long>(motions.size()) == 6 - lu.rank());
  }
  CHECK(checked > 40);
}

}  // namespace xshell::test
