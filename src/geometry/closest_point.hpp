// Closest points on triangles and on triangle meshes: the target surface of
// the inverse design attracts each targeted joint to its closest point.
//
// The squared distance d(x)^2 = |x - c(x)|^2 to a closed set is differentiable
// wherever the closest point c(x) is unique, with gradient 2 (x - c(x)): the
// fit term needs no derivative of c.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace xshell {

// The point of triangle abc closest to p (degenerate triangles included:
// a segment or a point). Ericson, Real-Time Collision Detection, 5.1.5.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

struct ClosestPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int triangle = -1;
  double distance = 0.0;
};

// A bounding-volume hierarchy of axis-aligned boxes over a triangle mesh:
// closest-point queries visit the boxes nearest first and skip those
// farther than the best point found.
class TriangleTree {
 public:
  // Throws std::invalid_argument for no triangles, an index outside
  // `vertices` or a non-finite vertex.
  TriangleTree(std::vector<Eigen::Vector3d> vertices, std::vector<std::array<int, 3>> triangles);

  ClosestPoint closest(const Eigen::Vector3d& p) const;
  int num_triangles() const { return static_cast<int>(triangles_.size()); }
  const Eigen::AlignedBox3d& bounds() const { return nodes_.front().box; }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0, count = 0;   // leaf: order_[first, first + count)
    int left = -1, right = -1;  // children (inner nodes)
  };
  int build(int first, int count);
  Eigen::AlignedBox3d triangle_box(int t) const;
  Eigen::Vector3d centroid(int t) const;

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<int> order_;  // triangles, grouped by leaf
  std::vector<Node> nodes_;
};

}  // namespace xshell
