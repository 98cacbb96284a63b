// The rods file (.vtp): the centerlines of a snapshot, one polyline cell per
// full rod, so that ParaView can draw each rod as a tube or colour it by the
// per-node energy densities.
//
// Layout. Points are the rods' nodes, rod after rod in snapshot order (a
// joint's position appears once per rod through it; points are not shared).
//   cell data   rod_id             int      the rod's id
//   point data  segment_id         int      graph segment of the node's edge:
//                                           the edge before it, or after it at
//                                           the rod's first node
//               curvature          double   1/length
//               twist              double   rad/length
//               bending_density    double   energy/length
//               twisting_density   double   energy/length
// Per-edge quantities (material frame, stretching) cannot be cell data of a
// per-rod polyline; they are in the frames file (frames_file.hpp).
#pragma once

#include <filesystem>

#include "snapshot.hpp"
#include "write_options.hpp"

namespace xshell {

// Throws std::invalid_argument for an inconsistent snapshot (see validate)
// and OutputError naming `path` when it cannot be written.
void write_rods_file(const Snapshot& snapshot, const std::filesystem::path& path,
                     const WriteOptions& options = {});

}  // namespace xshell
