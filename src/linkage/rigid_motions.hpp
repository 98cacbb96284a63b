// Rigid motions of a whole linkage that its supports leave free.
//
// A rigid motion moves every point x with velocity v(x) = t + w x x
// (translation t, rotation w about the origin). The elastic energy does not
// change along it, so a rigid motion that no support holds is a zero mode of
// the elastic Hessian: only the loads can hold it (a pendulum under gravity),
// and where they do not, Newton's system is singular and the equilibrium is
// not unique (a free linkage under a horizontal force has none at all).
//
// Each fixed scalar is one linear equation on (t, w) in R^6:
//   - a position component c (joint p or free-end node, at x):
//       t_c + (w x x)_c = 0,  i.e. [e_c, x x e_c] . (t, w) = 0;
//   - "orientation", at a joint or a free end: the joint's frame (or the
//     clamped end edge and its theta) turns with every rotation: w = 0;
//   - "opening_angle" holds no rigid motion.
// The motions left free are the null space of these equations (to first
// order, at the given positions).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "statics_problem.hpp"

namespace xshell {

struct RigidMotion {
  enum class Kind { Translation, Rotation };
  Kind kind = Kind::Translation;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit: translation or rotation axis
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // rotations: a point of the axis (model frame)
};

// The rigid motions (a basis, translations first, coordinate axes where
// possible) that `supports` leave free. vertex_positions: every graph
// vertex's position (a joint's p or a free end's node), indexed like
// VertexSupport::vertex; supports naming other vertices are ignored.
std::vector<RigidMotion> free_rigid_motions(const std::vector<VertexSupport>& supports,
                                            const std::vector<Eigen::Vector3d>& vertex_positions);

// "translation along x; rotation about [0.6, 0.8, 0] through (1, 2, 0)":
// one line, points shifted by `origin` (the user's coordinates).
std::string describe(const std::vector<RigidMotion>& motions,
                     const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

}  // namespace xshell
