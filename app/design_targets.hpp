// The targets of `xshell design` (the "design" section of a configuration,
// io/config.hpp) in the model's coordinates: the input's, mapped by the
// configuration's "transform" and recentred by the problem's origin.
//   target_joints:  the vertices with a position in the file, at it;
//   target_surface: every joint, attracted at each evaluation to the closest
//                   point of the surface to its deployed position (an AABB
//                   tree, geometry/closest_point.hpp).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "geometry/closest_point.hpp"
#include "integrators/design/vertex_targets.hpp"
#include "io/config.hpp"

namespace xshell {

struct DesignTargets {
  std::vector<VertexTarget> targets;
  std::shared_ptr<const TriangleTree> surface;  // null for target_joints
  // For a surface: moves the targets to the closest points (DesignOptions::retarget).
  std::function<void(const RodLinkage&, std::vector<VertexTarget>&)> retarget;
};

// Reads the target file of config.design (which must be set) for `linkage`,
// placed at `origin`. Throws InputError naming the file.
DesignTargets read_design_targets(const Config& config, const RodLinkage& linkage,
                                  const Eigen::Vector3d& origin);

// Per graph vertex: the distance of its current position to its target (NaN
// for a vertex without one).
std::vector<double> target_distances(const RodLinkage& linkage,
                                     const std::vector<VertexTarget>& targets);

}  // namespace xshell
