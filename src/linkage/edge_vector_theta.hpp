// The closed forms of docs/model.md section 7.4 for the derivatives of a terminal edge's material
// angle theta^j with respect to the edge vectors e_A, e_B of an edge-vector joint (joint.hpp), in
// global coordinates.
//
// Terminal edge j lies on rod X (A or B) with orientation s_jX = +/-1: its
// edge vector is s_jX e_X, its unit tangent t^j = s_jX e_X / |e_X|. Its
// reference frame is the source frame (t_hat, d1_hat) parallel-transported
// to t^j, (d1_ref, d2_ref); theta^j turns it so that the material d2 equals
// the joint normal n = e_A x e_B / |e_A x e_B|, hence the material
// d1 = n x t^j.
//
// Gradient (4.1), at any configuration:
//   dtheta/de_A = -(t.e_B)/|e_A x e_B| n + s_jA (I - t_A t_A^T)/|e_A| g,
//   dtheta/de_B =  (t.e_A)/|e_A x e_B| n + s_jB (I - t_B t_B^T)/|e_B| g,
//   g = [(d1_hat.t)(d1_ref x t_hat) + (d2_ref.t_hat) d1_hat] / (1 + t_hat.t)
//       - (d1_hat.t)(d2_ref.t_hat) / (1 + t_hat.t)^2 t_hat + d1_hat x d1_ref,
// (s_jX = 0 when edge j is not on rod X). The first terms turn theta with the normal, the second
// subtract the turn of the reference frame by parallel transport; g vanishes at t = t_hat. Checked
// against forward-mode AD of Joint::terminal_edge (tests/linkage/edge_vector_theta_test.cpp;
// docs/model.md section 10.1): the seed note prints the d1 and d2 of the first two terms of g
// without the underline that marks the reference frame; they must be the REFERENCE directors
// (d1_ref, d2_ref), like the underlined d1_ref of the last term. With the material d1, d2 there,
// the gradient is off by 0.4 % to 77 % (relative, 40 random configurations away from t = t_hat);
// with the reference ones it agrees to 1e-15.
//
// Hessian (4.2), valid right after a source-frame update (t^j = t_hat):
//   H_AA = -(d2 d1^T + d1 d2^T) / (2 |e_A|^2) delta_jA
//          + (t.e_B) / |e_A x e_B|^2 (I - 2 n n^T) [e_B]x,
//   H_BB = -(d2 d1^T + d1 d2^T) / (2 |e_B|^2) delta_jB
//          + (t.e_A) / |e_A x e_B|^2 (I - 2 n n^T) [e_A]x,
//   H_AB = d2 theta / de_A de_B  (rows: e_A, columns: e_B)
//        = -n t^T / |e_A x e_B| - (t.e_B) / |e_A x e_B|^2 (I - 2 n n^T) [e_A]x,
// with (d1, d2) the material frame (d2 = n) and delta_jX = s_jX^2. All three
// blocks agree with AD to round-off at the update; the cross block has the
// orientation stated (its transpose is wrong by O(1)). Away from the update
// the transport term's second derivative no longer reduces to [t]x / 2 and
// these blocks are only approximations (the model itself uses the exact AD
// derivatives everywhere).
#pragma once

#include <Eigen/Core>

#include "rod/frames.hpp"

namespace xshell {

// One terminal edge j of an edge-vector joint.
struct EdgeVectorThetaStencil {
  Eigen::Vector3d e_a = Eigen::Vector3d::UnitX();  // the joint's edge vectors, global
  Eigen::Vector3d e_b = Eigen::Vector3d::UnitY();
  int label = 0;       // rod of edge j: 0 (A) or 1 (B)
  int sign = 1;        // s_jX: +1 when edge j is e_X, -1 when it is -e_X
  SourceFrame source;  // edge j's source frame (t_hat, d1_hat)
};

// Blocks of the Hessian of theta^j with respect to (e_A, e_B).
struct EdgeVectorThetaHessian {
  Eigen::Matrix3d aa, bb;
  Eigen::Matrix3d ab;  // d2 theta / de_A de_B: rows e_A, columns e_B
  // The 6 x 6 Hessian in the order (e_A, e_B).
  Eigen::Matrix<double, 6, 6> full() const;
};

// g above: d1_ref . d(P_{t_hat}^{t} d2_hat)/dt, before projection onto the
// plane orthogonal to t (t unit).
Eigen::Vector3d transport_turn_gradient(const Eigen::Vector3d& t, const SourceFrame& source);

// docs/model.md section 7.4, gradient: (dtheta/de_A, dtheta/de_B), any configuration.
Eigen::Matrix<double, 6, 1> edge_vector_theta_gradient(const EdgeVectorThetaStencil& stencil);

// docs/model.md section 7.4, Hessian blocks: valid when the source frame was set at the current
// tangent (stencil.source.tangent = t^j); stencil.source is not read.
EdgeVectorThetaHessian edge_vector_theta_hessian(const EdgeVectorThetaStencil& stencil);

}  // namespace xshell
