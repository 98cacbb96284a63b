// Conversions between the two parametrizations of one joint state (joint.hpp): rotation joints (p,
// omega, alpha, l_A, l_B with a bisector frame; docs/model.md section 5.2) and edge-vector joints
// (p, c_A, c_B; docs/model.md section 5.4). Both describe the same geometry, the position p and the
// two edge vectors, with the normal n = e_A x e_B / |e_A x e_B|:
//   rotation -> edge vectors: e_X = l_X t_X, expressed in bases aligned
//     with the current directions, so c_X = (l_X, 0, 0);
//   edge vectors -> rotation: alpha = angle(e_A, e_B) in (0, pi),
//     l_X = |e_X|, and a bisector frame that reproduces the directions with
//     omega = 0.
// The terminal edges (nodes and theta) of every incident segment are the same before and after
// (tested in tests/linkage/edge_vector_joint_test.cpp).
#pragma once

#include <Eigen/Core>

#include "joint.hpp"

namespace xshell {

// A joint's geometry as its edge vectors e_A, e_B in global coordinates (docs/model.md section
// 5.4).
struct JointEdgeVectors {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d e_a = Eigen::Vector3d::UnitX();
  Eigen::Vector3d e_b = Eigen::Vector3d::UnitY();
};

// Position and edge vectors of a joint of either kind.
JointEdgeVectors edge_vectors(const Joint& joint);

// A joint of the given kind with this geometry (normal e_a x e_b /
// |e_a x e_b|, omega = 0, bases aligned). Throws std::domain_error when an
// edge vector vanishes or, for an edge-vector joint, when e_a and e_b are
// within kMinEdgeVectorAngleDegrees of parallel.
Joint joint_from_edge_vectors(const JointEdgeVectors& geometry, JointKind kind);

// The same joint state in the parametrization `kind` (a copy when it is
// already of that kind). Throws std::domain_error as above, and for a
// rotation joint whose opening angle has left (0, pi): its normal is then
// -e_A x e_B, which no edge-vector joint can represent.
Joint convert_joint(const Joint& joint, JointKind kind);

}  // namespace xshell
