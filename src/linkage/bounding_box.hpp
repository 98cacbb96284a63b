// The axis-aligned bounding box of a point set: a linkage's vertices. Its
// centre is the origin a linkage is moved to (the configuration's reader,
// state.json's "origin"), its diagonal the linkage's length scale; a
// picture's camera looks at the centre of the box of what it shows.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace xshell {

// Default: the empty box, which extend() grows to hold each point (its
// centre is the origin while it stays empty).
struct BoundingBox {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(std::numeric_limits<double>::lowest());

  void extend(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Eigen::Vector3d centre() const { return 0.5 * (lo + hi); }
  Eigen::Vector3d diagonal() const { return hi - lo; }
};

// Of a non-empty point set (std::out_of_range for an empty one).
inline BoundingBox bounding_box(const std::vector<Eigen::Vector3d>& points) {
  BoundingBox box{points.at(0), points.at(0)};
  for (const auto& p : points) box.extend(p);
  return box;
}

}  // namespace xshell
