// Derivatives of a joint's geometry and of the terminal edges it controls
// with respect to its 9 parameters: what the chain rule through the joints
// needs (linkage_assembly.hpp applies them to every segment).
#pragma once

#include <Eigen/Core>

#include "joint.hpp"

namespace xshell {

// Jacobian (7 x 9) of a joint's terminal edge (joint.hpp) with respect to
// its parameters, by first-order forward AD: what gradients need, without
// the 7 Hessians of Joint::terminal_edge_derivatives.
void terminal_edge_jacobian(const Joint& joint, int label, int sign, const SourceFrame& source,
                            double theta_hint, Eigen::Matrix<double, 7, 9>& jacobian);

// A joint's edge vectors and normal, v = (e_A, e_B, n), with their exact
// first and second derivatives with respect to its parameters. For both
// joint kinds they depend on parameters 3..8 only (omega, alpha, l_A, l_B or
// e_A, e_B; never on the position p), so they are taken by second-order
// forward AD of Joint::geometry over those 6, once per joint.
struct JointGeometryDerivatives {
  Eigen::Matrix<double, 9, 1> value;
  Eigen::Matrix<double, 9, 6> jacobian;     // row k: d v_k / d params[3..8]
  Eigen::Matrix<double, 6, 6> hessians[9];  // d2 v_k / d params[3..8]^2
};
// Rotation joints take a shorter road (AD over the rotation vector alone,
// the rest by hand); edge-vector joints, and the test of that road, take
// second-order AD over all six.
void joint_geometry_derivatives(const Joint& joint, JointGeometryDerivatives& out);
void joint_geometry_derivatives_by_ad(const Joint& joint, JointGeometryDerivatives& out);
// The same values and Jacobian by first-order AD (hessians untouched): what
// gradients need.
void joint_geometry_jacobian(const Joint& joint, JointGeometryDerivatives& out);

// Jacobian and Hessians of a terminal edge's 7 values (first node, second
// node, theta) with respect to the joint's 9 parameters, as
// Joint::terminal_edge_derivatives gives them, from the joint's geometry
// derivatives. The nodes p -/+ sign e_X / 2 are linear in p and e_X. theta =
// atan2(-n . d1_ref, n . d2_ref) of the edge e = sign e_X has, with
// y = -n . d1_ref, x = n . d2_ref, t = e/|e| and kh the source curvature
// binormal (vertex_stencil.hpp),
//   dtheta/dn = -(x d1_ref + y d2_ref) / (x^2 + y^2),
//   dtheta/de = (I - t t^T) [(n . t)(x d1_ref + y d2_ref) / (x^2 + y^2) + kh / 2] / |e|,
// whose Jacobian (first-order AD over (e, n)) is its Hessian; both are
// chained through the geometry. No value depends on p nonlinearly, so the
// Hessians are stored over parameters 3..8 only.
struct TerminalEdgeDerivatives {
  Eigen::Matrix<double, 7, 9> jacobian;
  Eigen::Matrix<double, 6, 6> hessians[7];  // over params[3..8]; zero elsewhere
};
void terminal_edge_derivatives(const JointGeometryDerivatives& geometry, int label, int sign,
                               const SourceFrame& source, TerminalEdgeDerivatives& out);
// Its Jacobian alone, from the geometry's values and Jacobian (as
// joint_geometry_jacobian gives them): the gradient's chain rule.
void terminal_edge_jacobian(const JointGeometryDerivatives& geometry, int label, int sign,
                            const SourceFrame& source, Eigen::Matrix<double, 7, 9>& jacobian);

}  // namespace xshell
