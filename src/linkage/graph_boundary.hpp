// The boundary of a linkage graph: its outer rim and its free rod ends, what
// a support selects with "select": "boundary" (README, "Supports").
#pragma once

#include <vector>

#include "graph.hpp"

namespace xshell {

// The vertices on the outer rim of `graph`, sorted: those met walking around
// the outside of its drawing projected onto the best-fit plane of its
// vertices (the plane through their centroid normal to the direction of least
// spread), dangling chains that stick out included, and every free rod end
// (valence 1), wherever it is. Holes inside the linkage are not its rim.
// Throws ModelError when two edges of the projected drawing cross (the walk
// would not be the rim then: a graph curved too far to lie over a plane), or
// when the graph has no edge.
std::vector<int> boundary_vertices(const LineGraph& graph);

}  // namespace xshell
