#include "frame_free_unknowns.hpp"

namespace xshell {

std::vector<bool> frame_free_unknowns(const RodLinkage& linkage) {
  std::vector<bool> free(linkage.num_dofs(), false);
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const int positions = 3 * linkage.segment(s).num_nodes();  // then the thetas
    for (int full = 0; full < positions; ++full) {
      const int r = linkage.reduced_index(s, full);
      if (r >= 0) free[r] = true;
    }
  }
  for (int j = 0; j < linkage.num_joints(); ++j) {
    const int offset = linkage.joint_dof_offset(j);
    const bool rotation = linkage.joint(j).kind() == JointKind::Rotation;
    for (int k = 0; k < 9; ++k) free[offset + k] = !(rotation && k >= kOmega && k < kOmega + 3);
  }
  return free;
}

}  // namespace xshell
