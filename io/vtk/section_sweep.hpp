// Geometry of a rod swept by its cross-section, for the solids file. Pure
// functions, no VTK.
//
// A cross-section is drawn in the plane of the material frame: a point with
// section coordinates (a, b) sits at  x + a d1 + b d2  (width along d1, height
// along d2, as in SectionSnapshot). Edges carry the material frame; a node
// needs one too, so interior nodes average the frames of their two edges:
//   t = normalize(t_prev + t_next),
//   d1 = normalize(P_t (d1_prev + d1_next)),   P_t = I - t t^T,
//   d2 = t x d1.
// The section is placed perpendicular to that averaged tangent (a miter joint
// without the 1/cos(turning/2) stretch, negligible for short edges). The
// returned frame is always right-handed, d1 x d2 = t; rectangles and
// ellipses are symmetric about d1, so a left-handed input frame gives the same
// solid.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "snapshot.hpp"

namespace xshell {

// Section outline in section coordinates (a, b), counter-clockwise (from +d1
// towards +d2), centred on the rod axis: the 4 corners of a rectangle, or
// `ellipse_sides` points on an ellipse starting at (width/2, 0). Throws
// std::invalid_argument when width or height is not positive or
// ellipse_sides < 3.
std::vector<Eigen::Vector2d> section_outline(const SectionSnapshot& section, int ellipse_sides);

struct NodeFrame {
  Eigen::Vector3d tangent;  // unit
  Eigen::Vector3d d1;       // unit, orthogonal to tangent
  Eigen::Vector3d d2;       // tangent x d1
};

// One frame per node of `rod` (n + 1 entries); end nodes take the frame of
// their edge. An edge of zero length takes the tangent of its nearest edge
// that has one (never throws: any rod short of non-finite nodes is drawn).
std::vector<NodeFrame> node_frames(const RodSnapshot& rod);

}  // namespace xshell
