// The joints file (.vtp): one vertex cell per joint at its position.
//
// Layout. Points are joints in snapshot order.
//   point data  vertex         int         graph vertex index (0-based)
//               normal         3 x double  joint normal (unit)
//               opening_angle  double      radians, in (0, pi)
//               valence        int         number of segments at the joint
//               pin_force_a    3 x double  force the pin applies to rod A (force unit),
//               pin_force_b    3 x double  and to rod B; only when the snapshot has them
//               target_distance double     distance to the inverse design's target (length
//                                          unit; NaN without one); only when a joint has one
#pragma once

#include <filesystem>

#include "snapshot.hpp"
#include "write_options.hpp"

namespace xshell {

// Throws OutputError naming `path` when it cannot be written.
void write_joints_file(const Snapshot& snapshot, const std::filesystem::path& path,
                       const WriteOptions& options = {});

}  // namespace xshell
