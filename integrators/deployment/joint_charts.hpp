// A rotation joint's omega is measured from its reference frame R0, which
// every rebase replaces (Joint::fold: R0 <- R(omega) R0, omega <- 0). The
// omegas of two equilibria of a path are therefore in different charts,
// and their difference means nothing until both are expressed in one
// (docs/model.md 9.3). Here the earlier equilibrium's omegas, and those of
// its tangent, are re-expressed in the joints' current frames:
//   F = R(omega) R0 (the joint's frame itself, chart-free),
//   omega' = log(F R0_now^T),
//   domega' = J_l(omega')^-1 J_l(omega) domega
// (the same spatial angular velocity J_l(omega) domega, rotation.hpp).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "integrators/deployment/path_predictor.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

// The rotation joints whose three omegas are all free unknowns.
struct FreeRotation {
  int joint = 0;
  std::array<int, 3> free = {0, 0, 0};  // indices of omega among the free unknowns
};

std::vector<FreeRotation> free_rotations(const LinkageProblem& problem);

// The frames F = R(omega) R0 of those joints, in that order.
std::vector<Eigen::Matrix3d> joint_frames(const RodLinkage& linkage,
                                          const std::vector<FreeRotation>& rotations);

// `point` (with the frames its omegas were measured in, PathPoint::frames)
// with its omegas (and its tangent's, when it has one) in the charts of
// `linkage`'s joints now.
PathPoint in_current_charts(const PathPoint& point, const RodLinkage& linkage,
                            const std::vector<FreeRotation>& rotations);

}  // namespace xshell
