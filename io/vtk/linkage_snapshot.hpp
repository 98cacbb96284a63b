// The linkage as the VTK writers draw it: one polyline per full rod, across
// its segments (the terminal edge two segments share at a joint appears
// once), with material frames per edge and curvature, twist and energy
// densities per node; one point per joint.
#pragma once

#include "linkage/rod_linkage.hpp"
#include "snapshot.hpp"

namespace xshell {

// origin is added to every position (the model works in recentred
// coordinates); time is the snapshot's time stamp.
Snapshot linkage_snapshot(const RodLinkage& linkage, const Eigen::Vector3d& origin, double time);

}  // namespace xshell
