// Which rods pass through which joints, and how each joint is oriented.
//
// Segments (graph edges) are glued into full rods at joints by the
// straightest path in the input (docs/model.md section 2.2): at a valence-4 vertex the
// pair of segments whose directions are closest to opposite forms one rod,
// the other two the second rod; at valence 3 the straightest pair passes
// through and the third segment's rod ends there; at valence 2 two rod ends
// are pinned together. Valence-1 vertices are free rod ends.
//
// Every rod gets a direction and every joint labels its two rods A and B so
// that (t_A x t_B) . n > 0, with n the joint normal and t_X the rod's tangent
// there, oriented along the rod; the opening angle alpha = angle(t_A, t_B)
// then lies in (0, pi). Normals are oriented breadth first so that
// neighbouring joints agree (a non-orientable linkage is rejected), and rod
// directions are propagated breadth first through the joints so that a rod
// carries the same label at its joints and alpha measures the same opening
// on both sides of a rod: raising alpha everywhere opens the linkage. Curved
// rods that cross the same rod twice meet it with opposite orientations at
// the two crossings; no labelling can agree at both, and the second crossing
// reached keeps its own geometric labels.
//
// Normals: n = t_A x t_B / |t_A x t_B|, except where the two rods are within
// kCollinearDegrees of collinear (common at valence-2 vertices of real
// designs), where that cross product is no normal: there n is the average
// normal of the nearest regular joints (breadth first through the graph), or
// failing that the normal of the best-fit plane of the vertex's neighbourhood,
// and the rod tangents are projected onto the plane orthogonal to n. Such
// joints take no part in propagating labels and directions.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "graph.hpp"

namespace xshell {

constexpr double kCollinearDegrees = 8.0;

// One segment end at a joint.
struct SegmentEnd {
  int segment = -1;
  bool at_start = true;  // the segment's first node (graph edge[0]) is at this joint
  // +1 when the segment's own direction (edge[0] -> edge[1]) agrees with the
  // rod tangent t_X at this joint, -1 otherwise.
  int sign = 1;
};

struct JointTopology {
  int vertex = -1;
  // Segment ends of rod A (index 0) and rod B (index 1): one or two each.
  std::array<std::vector<SegmentEnd>, 2> ends;
  std::array<int, 2> rod = {-1, -1};       // full rod of A and B
  std::array<Eigen::Vector3d, 2> tangent;  // unit t_A, t_B, orthogonal to the normal
  Eigen::Vector3d normal;                  // unit
  double opening_angle = 0.0;              // angle(t_A, t_B) in (0, pi)
  bool collinear = false;                  // normal taken from the neighbourhood
};

struct SegmentTopology {
  std::array<int, 2> vertex = {-1, -1};  // graph edge
  std::array<int, 2> joint = {-1, -1};   // joint index at start and end, -1 at a free end
  std::array<int, 2> label = {-1, -1};   // 0 (A) or 1 (B) at that joint
  std::array<int, 2> sign = {1, 1};      // SegmentEnd::sign at start and end
  int rod = -1;
  double length = 0.0;  // graph edge length
};

struct RodChain {
  std::vector<int> segments;  // in rod order
  std::vector<bool> forward;  // segment direction agrees with the rod's
};

struct LinkageTopology {
  std::vector<int> valence;               // per vertex
  std::vector<int> joint_of_vertex;       // per vertex, -1 for free ends
  std::vector<JointTopology> joints;      // in vertex order
  std::vector<SegmentTopology> segments;  // in edge order
  std::vector<RodChain> rods;
};

// Throws ModelError when the graph cannot form a linkage (valence above 4,
// rods that cannot be split into two families, ...).
LinkageTopology build_topology(const LineGraph& graph);

}  // namespace xshell
