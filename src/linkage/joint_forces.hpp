// Forces that the scissor joints (pins) transmit between their two rods.
//
// A joint's position p carries the terminal edges of both rods' segments
// (nodes p -/+ e_X / 2), so the force the pin applies to rod X is the sum,
// over X's segments at the joint, of d(E_s - W_s)/dp: the generalized force
// that holds those segments' terminal nodes where they are. At an
// equilibrium the pin itself is balanced,
//   force_on[A] + force_on[B] = load at the joint + support reaction,
// so without either, force_on[A] = -force_on[B]: the force rod B pushes
// into rod A through the pin, what a connector must carry.
// For rotation joints also the moment the pin applies to rod X about p, from
// a rigid rotation of X's terminal edges (as in reactions.hpp):
// J_l(omega)^-T d(E_X)/domega. It has no component along the joint normal
// (the pin turns freely there) unless the opening angle is held by a
// support. Edge-vector joints report no moment.
// Units: force unit, force x length.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "statics_problem.hpp"

namespace xshell {

struct JointForce {
  int vertex = 0;                    // graph vertex of the joint
  std::array<int, 2> rod{{-1, -1}};  // full rod of A and B (topology.hpp)
  std::array<Eigen::Vector3d, 2> force_on{{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
  std::optional<std::array<Eigen::Vector3d, 2>> moment_on;  // rotation joints
};

// Per joint, in joint (vertex) order, at the current state.
std::vector<JointForce> joint_forces(const LinkageProblem& problem);

}  // namespace xshell
