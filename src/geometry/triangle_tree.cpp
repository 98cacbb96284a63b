// TriangleTree (closest_point.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "closest_point.hpp"

namespace xshell {

namespace {

constexpr int kLeafSize = 4;

}  // namespace

TriangleTree::TriangleTree(std::vector<Eigen::Vector3d> vertices,
                           std::vector<std::array<int, 3>> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  if (triangles_.empty()) throw std::invalid_argument("triangle mesh: no triangles");
  for (const Eigen::Vector3d& v : vertices_)
    if (!v.allFinite()) throw std::invalid_argument("triangle mesh: a vertex is not finite");
  const int nv = static_cast<int>(vertices_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (int i : triangles_[t])
      if (i < 0 || i >= nv)
        throw std::invalid_argument("triangle mesh: triangle " + std::to_string(t) +
                                    " uses vertex " + std::to_string(i) + " of " +
                                    std::to_string(nv));
  order_.resize(triangles_.size());
  for (std::size_t t = 0; t < order_.size(); ++t) order_[t] = static_cast<int>(t);
  nodes_.reserve(2 * triangles_.size() / kLeafSize + 2);
  build(0, static_cast<int>(order_.size()));
}

Eigen::AlignedBox3d TriangleTree::triangle_box(int t) const {
  Eigen::AlignedBox3d box;
  for (int i : triangles_[t]) box.extend(vertices_[i]);
  return box;
}

Eigen::Vector3d TriangleTree::centroid(int t) const {
  const std::array<int, 3>& tri = triangles_[t];
  return (vertices_[tri[0]] + vertices_[tri[1]] + vertices_[tri[2]]) / 3.0;
}

// Splits order_[first, first + count) at the median of the centroids along
// the longest axis of their box; returns the node's index.
int TriangleTree::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, centres;
  for (int k = first; k < first + count; ++k) {
    box.extend(triangle_box(order_[k]));
    centres.extend(centroid(order_[k]));
  }
  nodes_[index].box = box;
  nodes_[index].first = first;
  nodes_[index].count = count;
  if (count <= kLeafSize) return index;
  int axis = 0;
  centres.sizes().maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count,
                   [&](int s, int t) { return centroid(s)[axis] < centroid(t)[axis]; });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].left = left;
  nodes_[index].right = right;
  nodes_[index].count = 0;
  return index;
}

ClosestPoint TriangleTree::closest(const Eigen::Vector3d& p) const {
  ClosestPoint best;
  double best2 = INFINITY;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (node.box.squaredExteriorDistance(p) >= best2) continue;
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const std::array<int, 3>& tri = triangles_[order_[k]];
        const Eigen::Vector3d q =
            closest_point_on_triangle(p, vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]);
        const double d2 = (q - p).squaredNorm();
        if (d2 < best2) best2 = d2, best.point = q, best.triangle = order_[k];
      }
      continue;
    }
    // The nearer child last, so that it is visited first.
    const double dl = nodes_[node.left].box.squaredExteriorDistance(p);
    const double dr = nodes_[node.right].box.squaredExteriorDistance(p);
    stack.push_back(dl < dr ? node.right : node.left);
    stack.push_back(dl < dr ? node.left : node.right);
  }
  best.distance = std::sqrt(best2);
  return best;
}

}  // namespace xshell
