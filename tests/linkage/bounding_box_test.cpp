// The bounding box of a linkage's vertices (linkage/bounding_box.hpp): its
// centre is the origin a linkage is moved to, its diagonal the length scale.
#include "linkage/bounding_box.hpp"

#include <doctest/doctest.h>

#include <stdexcept>

namespace xshell::test {

TEST_CASE("Bounding box: corners, centre and diagonal of a point set") {
  const std::vector<Eigen::Vector3d> points = {
      {1.0, -2.0, 0.5}, {-3.0, 4.0, 0.5}, {2.0, 1.0, -1.5}, {0.0, 0.0, 0.0}};
  const BoundingBox box = bounding_box(points);
  CHECK(box.lo == Eigen::Vector3d(-3.0, -2.0, -1.5));
  CHECK(box.hi == Eigen::Vector3d(2.0, 4.0, 0.5));
  CHECK(box.centre() == Eigen::Vector3d(-0.5, 1.0, -0.5));
  CHECK(box.diagonal() == Eigen::Vector3d(5.0, 6.0, 2.0));
  // The order of the points does not matter.
  const std::vector<Eigen::Vector3d> reversed(points.rbegin(), points.rend());
  CHECK(bounding_box(reversed).lo == box.lo);
  CHECK(bounding_box(reversed).hi == box.hi);
}

TEST_CASE("Bounding box: a single point, and no points") {
  const BoundingBox box = bounding_box({Eigen::Vector3d(1.0, 2.0, 3.0)});
  CHECK(box.centre() == Eigen::Vector3d(1.0, 2.0, 3.0));
  CHECK(box.diagonal().norm() == 0.0);
  CHECK_THROWS_AS(bounding_box({}), std::out_of_range);
}

TEST_CASE("Bounding box: grown point by point from the empty box") {
  BoundingBox box;
  CHECK(box.centre() == Eigen::Vector3d::Zero());  // empty: the origin
  const std::vector<Eigen::Vector3d> points = {{1.0, -2.0, 0.5}, {-3.0, 4.0, 0.5}};
  for (const Eigen::Vector3d& p : points) box.extend(p);
  CHECK(box.lo == bounding_box(points).lo);
  CHECK(box.hi == bounding_box(points).hi);
  CHECK(box.centre() == Eigen::Vector3d(-1.0, 1.0, 0.5));
}

}  // namespace xshell::test
