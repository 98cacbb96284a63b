// The linkage graph: an embedded line mesh whose vertices are scissor joints
// (valence 2-4) or free rod ends (valence 1) and whose edges are rod
// segments. Vertices and edges keep the order of the input file; every index
// in the configuration, the unknowns and the outputs refers to that order.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace xshell {

struct LineGraph {
  std::vector<Eigen::Vector3d> vertices;  // positions, in the input's length unit
  std::vector<std::array<int, 2>> edges;  // 0-based vertex indices, in file order
};

// Number of edges incident to each vertex.
std::vector<int> valences(const LineGraph& graph);

// Vertices with the extreme x + y, x - y, -x + y, -x - y (the corners of a
// roughly rectangular plan), distinct, in that order of directions.
std::vector<int> corner_vertices(const LineGraph& graph);

}  // namespace xshell
