// The range of the opening angles and the joints outside (0, pi)
// (linkage/opening_angle_range.hpp).
#include "linkage/opening_angle_range.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

namespace xshell::test {

namespace {

// Two rods crossing at vertex 0 (opening angle pi/2), four free ends.
RodLinkage x_linkage() {
  LineGraph x;
  x.vertices = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
  x.edges = {{1, 0}, {0, 2}, {3, 0}, {0, 4}};
  LinkageOptions o;
  o.subdivisions = 4;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = 1e4;
  o.material.section = {SectionShape::Rectangle, 0.05, 0.03};
  return RodLinkage(x, o);
}

void set_alpha(RodLinkage& l, double alpha) {
  Eigen::VectorXd q = l.dofs();
  q[l.joint_dof_offset(0) + kAlpha] = alpha;
  l.set_dofs(q);
}

}  // namespace

TEST_CASE("Opening angle range: a joint closed through zero or opened through pi is listed") {
  RodLinkage l = x_linkage();
  const OpeningAngleRange built = opening_angle_range(l);
  REQUIRE(built.min.has_value());
  CHECK(*built.min == doctest::Approx(M_PI / 2));
  CHECK(*built.max == *built.min);
  CHECK(built.min_vertex == 0);
  CHECK(built.outside.empty());
  int listed = 0;
  for (double alpha : {-0.016, 0.0, M_PI, M_PI + 0.1}) {
    CAPTURE(alpha);
    set_alpha(l, alpha);
    const OpeningAngleRange range = opening_angle_range(l);
    REQUIRE(range.outside.size() == 1);
    CHECK(range.outside[0].vertex == 0);
    CHECK(range.outside[0].angle == alpha);
    CHECK(*range.min == alpha);
    ++listed;
  }
  CHECK(listed == 4);
  set_alpha(l, 1e-9);  // barely open: inside
  CHECK(opening_angle_range(l).outside.empty());
}

TEST_CASE("Opening angle range over per-vertex angles: free ends skipped, NaN outside") {
  const std::vector<std::optional<double>> angles = {
      1.0, std::nullopt, -0.2, 3.0, std::numeric_limits<double>::quiet_NaN(), 3.2, std::nullopt};
  const OpeningAngleRange range = opening_angle_range(angles);
  CHECK(*range.min == -0.2);
  CHECK(range.min_vertex == 2);
  CHECK(*range.max == 3.2);
  CHECK(range.max_vertex == 5);
  REQUIRE(range.outside.size() == 3);
  CHECK(range.outside[0].vertex == 2);
  CHECK(range.outside[1].vertex == 4);
  CHECK(std::isnan(range.outside[1].angle));
  CHECK(range.outside[2].vertex == 5);
  // No joints: no range.
  const OpeningAngleRange none = opening_angle_range(std::vector<std::optional<double>>(3));
  CHECK_FALSE(none.min.has_value());
  CHECK_FALSE(none.max.has_value());
  CHECK(none.outside.empty());
}

}  // namespace xshell::test
