// set_dofs must be a function of its argument: the solvers evaluate trial
// points far away and come back (a line search), and KINSOL and IDA assume
// that F(q) does not depend on where they evaluated before.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "linkage/rod_linkage.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

TEST_CASE(
    "set_dofs does not depend on the points visited before: a joint turned past pi and back") {
  RodLinkage linkage(grid(3, 3, 0.2), test_options(RestShape::Straight));
  const Eigen::VectorXd start = linkage.dofs();
  const double energy = linkage.energy().total();
  std::vector<Eigen::VectorXd> rods;
  for (int s = 0; s < linkage.num_segments(); ++s) rods.push_back(linkage.segment(s).dofs());

  // Turn the middle joint in steps of 0.5 rad to 4 rad (past pi) about an
  // oblique axis, the way a line search may wander, then jump back.
  const int j = linkage.topology().joint_of_vertex[4];
  REQUIRE(j >= 0);
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 1.0, 0.4).normalized();
  // Along the way, follow every terminal theta continuously (unwrapped step
  // by step): a hint taken from the last point visited would have carried
  // one of them more than pi away, to another branch when jumping back.
  auto terminal_thetas = [&] {
    std::vector<double> t;
    for (int s = 0; s < linkage.num_segments(); ++s)
      t.insert(t.end(), {linkage.segment(s).thetas().front(), linkage.segment(s).thetas().back()});
    return t;
  };
  std::vector<double> previous = terminal_thetas(), travelled(previous.size(), 0.0);
  int visited = 0;
  for (int k = 1; k <= 8; ++k) {
    Eigen::VectorXd r = start;
    r.segment<3>(linkage.joint_dof_offset(j) + kOmega) += 0.5 * k * axis;
    linkage.set_dofs(r);
    CHECK(std::isfinite(linkage.energy().total()));
    const std::vector<double> now = terminal_thetas();
    for (size_t i = 0; i < now.size(); ++i)
      travelled[i] += std::remainder(now[i] - previous[i], 2.0 * M_PI);
    previous = now;
    ++visited;
  }
  double farthest = 0.0;
  for (double t : travelled) farthest = std::max(farthest, std::abs(t));
  CHECK(farthest > M_PI);
  CHECK(linkage.energy().total() > energy + 1e-3);  // far from the start indeed
  linkage.set_dofs(start);

  CHECK(visited == 8);
  CHECK(linkage.energy().total() == doctest::Approx(energy).epsilon(1e-12));
  int compared = 0;
  for (int s = 0; s < linkage.num_segments(); ++s) {
    CHECK((linkage.segment(s).dofs() - rods[s]).lpNorm<Eigen::Infinity>() < 1e-12);
    ++compared;
  }
  CHECK(compared == linkage.num_segments());

  // The same after a source-frame update: the hints are those of the update.
  linkage.update_source_frames();
  const Eigen::VectorXd here = linkage.dofs();
  const double energy_here = linkage.energy().total();
  Eigen::VectorXd far = here;
  for (int k = 1; k <= 8; ++k) {
    far.segment<3>(linkage.joint_dof_offset(j) + kOmega) =
        here.segment<3>(linkage.joint_dof_offset(j) + kOmega) + 0.5 * k * axis;
    linkage.set_dofs(far);
  }
  linkage.set_dofs(here);
  CHECK(linkage.energy().total() == doctest::Approx(energy_here).epsilon(1e-12));
}

TEST_CASE("nodes_at places the nodes where set_dofs would, without moving the linkage") {
  RodLinkage linkage(grid(3, 3, 0.2), test_options(RestShape::Input));
  const Eigen::VectorXd start = linkage.dofs();
  Eigen::VectorXd r = start;
  std::srand(5);
  r += 0.02 * Eigen::VectorXd::Random(r.size());  // joints, positions and thetas all moved
  const std::vector<std::vector<Eigen::Vector3d>> placed = linkage.nodes_at(r);

  CHECK(linkage.dofs() == start);
  RodLinkage moved = linkage;
  moved.set_dofs(r);
  REQUIRE(placed.size() == static_cast<size_t>(linkage.num_segments()));
  int differ = 0;
  for (int s = 0; s < linkage.num_segments(); ++s) {
    CAPTURE(s);
    CHECK(placed[s] == moved.segment(s).nodes());
    differ += placed[s] != linkage.segment(s).nodes() ? 1 : 0;
  }
  CHECK(differ == linkage.num_segments());

  // An invalid joint: set_dofs' error, and still nothing moved.
  const int j = 0;
  r[linkage.joint_dof_offset(j) + kLengthA] = -1.0;
  CHECK_THROWS_AS(linkage.nodes_at(r), std::domain_error);
  CHECK_THROWS_AS(moved.set_dofs(r), std::domain_error);
  CHECK(linkage.dofs() == start);
}

}  // namespace xshell::test
