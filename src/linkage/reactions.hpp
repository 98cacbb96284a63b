// Support reactions: the force and moment every support applies to the
// linkage at an equilibrium.
//
// At an equilibrium of E(r) - W(r) (elastic energy minus the work of the
// dead loads), the gradient g of the total energy vanishes on the free
// unknowns; on the fixed ones, g is the generalized force the support must
// supply (dE/dr - f - R = 0: a Lagrange multiplier of r_i = const). Per
// support it is turned into a force and a moment about the supported vertex:
//  - joint, "position" / "x" / "y" / "z": force = g_p on the fixed
//    components (a roller takes no force along its free directions);
//  - rotation joint, "orientation": a rigid rotation dphi of the joint
//    frame is R(omega + domega) = R(dphi) R(omega) with dphi = J_l(omega)
//    domega (math/rotation.hpp), so the moment is J_l(omega)^-T g_omega;
//  - edge-vector joint, "orientation": a rigid rotation turns both edge
//    vectors, de_X = dphi x e_X, so the moment is sum_X e_X x g_(e_X);
//  - "opening_angle": g_alpha, the torque that holds the two rods at their
//    angle (internal to the joint: equal and opposite on the two rods, so
//    it is no external moment and does not enter the balance);
//  - free rod end, "position": force = g_(x_end) (fixed components);
//    "orientation" (a clamp of the end edge x_end, x_next, theta, centred
//    on the vertex v = (x_end + x_next) / 2): force = g_(x_end) + g_(x_next),
//    moment about v
//    = e / 2 x (g_(x_next) - g_(x_end)) + g_theta (t + t x kh / 2),
//    e = x_next - x_end,
//    t = e_j / |e_j| of the end edge j, kh the curvature binormal from the
//    edge's source tangent (the twist that time-parallel transport adds,
//    vertex_stencil.hpp).
// Sum of reactions + loads = 0 (forces and moments) at an equilibrium, up
// to the free residual (tested).
//
// Units: forces in the force unit, moments in force x length, positions in
// the model's (recentred) coordinates.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "statics_problem.hpp"

namespace xshell {

struct SupportReaction {
  int vertex = 0;                                      // graph vertex
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // where it acts (model coordinates)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();     // on the linkage
  std::optional<Eigen::Vector3d> moment;  // about `position`, where orientation is fixed
  std::optional<double> opening_torque;   // where the opening angle is fixed
};

// One entry per support of problem.supports() (the default pin included),
// merged per vertex, in the order of first appearance. Evaluated at the
// current state (meaningful at an equilibrium).
std::vector<SupportReaction> support_reactions(const LinkageProblem& problem);

// Resultant of the dead loads (gravity on every node, point forces): total
// force and moment about the model origin.
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};
Wrench applied_load_resultant(const LinkageProblem& problem);

// Resultant of the reactions about the model origin.
Wrench reaction_resultant(const std::vector<SupportReaction>& reactions);

}  // namespace xshell
