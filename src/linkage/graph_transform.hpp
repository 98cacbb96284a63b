// A similarity transform of the input linkage ("transform" of the
// configuration, README "Transforms"): applied to the graph's vertices before
// anything else, so that supports, loads and outputs all see the transformed
// linkage.
#pragma once

#include <Eigen/Core>

#include "graph.hpp"

namespace xshell {

// Applied in this order: mirror (negate one coordinate), scale (about the
// origin), rotate about the x axis, then about y, then about z (angles in
// degrees, right-handed, about the origin), translate.
struct GraphTransform {
  int mirror = -1;                                       // the axis negated (0, 1, 2), or -1: none
  double scale = 1.0;                                    // > 0; also a change of length unit
  Eigen::Vector3d rotate_deg = Eigen::Vector3d::Zero();  // degrees about x, y, z
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();   // length (after scaling)

  bool is_identity() const;
  // The 3 x 3 linear part (mirror, scale, rotations) and the whole map x -> A x + t.
  Eigen::Matrix3d linear() const;
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const;
};

// `graph` with every vertex mapped by `transform`.
LineGraph transformed(const LineGraph& graph, const GraphTransform& transform);

}  // namespace xshell
