// fabrication.svg: the straight laths of a linkage laid out side by side, one
// row per rod, to be printed or read off while marking and drilling.
//
// Every lath is drawn straight, from its start (left, s = 0) to its end
// (right, s = its cut length), lengths to one scale for all laths (the
// longest one 1000 px wide), widths (the section's width, in the plane of
// the joints) to the same scale but at least 6 px. The lath is numbered by
// its rod (the rod_id of the VTK files) and family at its left, with its cut
// length at its right. A hole (a circle of class "hole") marks every joint
// station, numbered by the joint's OBJ vertex (0-based), so that the two
// holes with the same number are pinned together. A scale bar with the
// length unit closes the drawing.
//
// For tools: each lath is a <g class="lath" data-rod data-family
// data-length>, each hole carries data-rod, data-vertex and data-s.
#pragma once

#include <string>

#include "io/fabrication_file.hpp"

namespace xshell {

// The SVG document (UTF-8 text).
std::string fabrication_svg(const FabricationData& data, const FabricationUnits& units);

}  // namespace xshell
