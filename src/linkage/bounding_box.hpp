// The axis-aligned bounding box of a point set: a linkage's vertices. Its
// centre is the origin a linkage is moved to (the configuration's reader,
// state.json's "origin"), its diagonal the linkage's length scale.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace xshell {

struct BoundingBox {
  Eigen::Vector3d lo, hi;

  Eigen::Vector3d centre() const { return 0.5 * (lo + hi); }
  Eigen::Vector3d diagonal() const { return hi - lo; }
};

// Of a non-empty point set (std::out_of_range for an empty one).
inline BoundingBox bounding_box(const std::vector<Eigen::Vector3d>& points) {
  BoundingBox box{points.at(0), points.at(0)};
  for (const auto& p : points) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

}  // namespace xshell
