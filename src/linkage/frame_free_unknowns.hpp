// Which reduced unknowns mean the same thing whatever the solvers'
// re-expressions (RodLinkage::update_source_frames, fold_joints): node and
// joint positions, opening angles, terminal edge lengths and edge-vector
// joints' edge vectors. A rod's thetas are measured from its source frames
// and a rotation joint's omega from its folded frame, so their values at two
// states rebased in between cannot be compared. Differences of states along
// a path (a continuation's predictor) are meaningful on the first kind only.
#pragma once

#include <vector>

#include "rod_linkage.hpp"

namespace xshell {

// Per reduced unknown (RodLinkage::num_dofs()): true for the kinds above.
std::vector<bool> frame_free_unknowns(const RodLinkage& linkage);

}  // namespace xshell
