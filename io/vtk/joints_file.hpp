// The joints file (.vtp): one vertex cell per joint at its position.
//
// Layout. Points are joints in snapshot order.
//   point data  vertex         int         graph vertex index (0-based)
//               normal         3 x double  joint normal (unit)
//               opening_angle  double      radians, in (0, pi)
//               valence        int         number of segments at the joint
#pragma once

#include <filesystem>

#include "snapshot.hpp"
#include "write_options.hpp"

namespace xshell {

// Throws OutputError naming `path` when it cannot be written.
void write_joints_file(const Snapshot& snapshot, const std::filesystem::path& path,
                       const WriteOptions& options = {});

}  // namespace xshell
