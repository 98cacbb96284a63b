// The vertices each support of a configuration holds: its "vertex", or what
// its "select" selects in the linkage (config.hpp, SupportSelect).
#pragma once

#include <vector>

#include "config.hpp"

namespace xshell {

// Per entry of config.supports, in order, its vertices in increasing order,
// selected in `graph` (the input after config.transform; regions are boxes of
// its coordinates). Vertex indices must be in range (check_vertices). Throws
// InputError naming "supports[i].select" when a selector selects no vertex or
// when the boundary is not defined for this linkage, and naming both entries
// when two hold a common vertex's position component at different
// displacements.
std::vector<std::vector<int>> resolve_supports(const Config& config, const LineGraph& graph);

}  // namespace xshell
