// The frames file (.vtp): the per-edge data of a snapshot, one vertex cell per
// rod edge at the edge's midpoint. Glyph d1 and d2 in ParaView (Glyph filter,
// arrow, orientation d1 or d2) to see the material frames.
//
// Layout. Points are edge midpoints, rod after rod, edge after edge.
//   point data  d1, d2              3 x double  material frame (unit)
//               rod_id              int         the edge's rod id
//               segment_id          int         the edge's graph segment
//               stretching_density  double      energy/length
//               edge_length         double      length
#pragma once

#include <filesystem>

#include "snapshot.hpp"
#include "write_options.hpp"

namespace xshell {

// Throws std::invalid_argument for an inconsistent snapshot (see validate)
// and OutputError naming `path` when it cannot be written.
void write_frames_file(const Snapshot& snapshot, const std::filesystem::path& path,
                       const WriteOptions& options = {});

}  // namespace xshell
