// Target joint positions for the inverse design: a JSON file
//   {"positions": [[x, y, z] or null, ...]}
// with one entry per vertex of the linkage's OBJ file, in its order (null:
// no target for that vertex), in the input's length unit.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace xshell {

struct TargetJoints {
  std::vector<std::optional<Eigen::Vector3d>> positions;  // per vertex
  int count() const;                                      // vertices with a target
};

// Throws InputError "FILE: PATH: what is wrong" for an unreadable file,
// other keys, an entry that is neither null nor three finite numbers, a
// count other than `num_vertices`, or no target at all.
TargetJoints read_target_joints(const std::string& path, int num_vertices);
TargetJoints parse_target_joints(const std::string& text, const std::string& file,
                                 int num_vertices);

}  // namespace xshell
