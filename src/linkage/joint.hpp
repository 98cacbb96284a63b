// A scissor joint in the rotation-based parametrization (seed section 5),
// with a bisector frame.
//
// Parameters (9, in this order): position p (3), rotation vector omega (3),
// opening angle alpha, and the lengths l_A, l_B of the two terminal edges.
// The joint stores a reference frame R0 = [b1 b2 n0]: the bisector b1 of the
// two rods' tangents, b2 = n0 x b1, and the normal n0. Then
//   t_A = R(omega) R0 (cos(alpha/2), -sin(alpha/2), 0)
//   t_B = R(omega) R0 (cos(alpha/2),  sin(alpha/2), 0)
//   e_A = l_A t_A,  e_B = l_B t_B,  n = R(omega) n0,
// so alpha is the angle from t_A to t_B about n, in (0, pi), and the two rods
// open symmetrically about the bisector. Fixing omega ("orientation") holds
// the bisector and the normal still while alpha stays free.
//
// The joint sets the terminal edge of every incident segment: the edge
// sign * e_X is centred on p (nodes p -/+ sign * e_X / 2), and its material
// frame has d2 = n, which fixes the edge's theta relative to its reference
// frame (frames.hpp): theta = atan2(-n . d1_ref, n . d2_ref), on the branch
// nearest the previous value.
//
// After a fold (R0 <- R(omega) R0, omega <- 0) the configuration is the same
// and omega sits at 0, where rotation.hpp evaluates R exactly.
#pragma once

#include <Eigen/Core>

#include "math/rotation.hpp"
#include "rod/frames.hpp"
#include "rod/vertex_stencil.hpp"

namespace xshell {

using JointParams = Eigen::Matrix<double, 9, 1>;
using JointGradient = Eigen::Matrix<double, 9, 1>;
using JointHessian = Eigen::Matrix<double, 9, 9>;

enum JointParam { kPosition = 0, kOmega = 3, kAlpha = 6, kLengthA = 7, kLengthB = 8 };

// The geometry a joint imposes on one incident terminal edge: its two
// nodes (in the segment's order) and its theta, as 7 values
// (x_first (3), x_second (3), theta).
template <class T>
struct TerminalEdge {
  V3<T> first, second;
  T theta;
};

class Joint {
 public:
  Joint() = default;
  // A joint at p whose rods have unit tangents t_a, t_b orthogonal to the
  // unit normal n, with terminal edge lengths l_a, l_b.
  Joint(const Eigen::Vector3d& p, const Eigen::Vector3d& t_a, const Eigen::Vector3d& t_b,
        const Eigen::Vector3d& n, double l_a, double l_b);

  const JointParams& params() const { return params_; }
  void set_params(const JointParams& params) { params_ = params; }
  const Eigen::Matrix3d& reference_frame() const { return frame_; }
  void set_reference_frame(const Eigen::Matrix3d& frame) { frame_ = frame; }

  Eigen::Vector3d position() const { return params_.segment<3>(kPosition); }
  double opening_angle() const { return params_[kAlpha]; }
  Eigen::Vector3d normal() const;
  // Unit tangent of rod `label` (0: A, 1: B).
  Eigen::Vector3d tangent(int label) const;

  // Folds omega into the reference frame; the geometry is unchanged.
  void fold();

  // Edge vectors and normal as functions of the parameters.
  template <class T>
  void geometry(const T* q, V3<T>& e_a, V3<T>& e_b, V3<T>& n) const;

  template <class T>
  TerminalEdge<T> terminal_edge(const T* q, int label, int sign, const SourceFrame& source,
                                double theta_hint) const;

  // The terminal edge at the current parameters, and its exact first and
  // second derivatives: jacobian (7 x 9) and one 9 x 9 Hessian per value.
  TerminalEdge<double> terminal_edge(int label, int sign, const SourceFrame& source, double theta_hint) const;
  void terminal_edge_derivatives(int label, int sign, const SourceFrame& source, double theta_hint,
                                 Eigen::Matrix<double, 7, 9>& jacobian, JointHessian hessians[7]) const;

 private:
  JointParams params_ = JointParams::Zero();
  Eigen::Matrix3d frame_ = Eigen::Matrix3d::Identity();  // columns b1, b2, n0
};

template <class T>
void Joint::geometry(const T* q, V3<T>& e_a, V3<T>& e_b, V3<T>& n) const {
  using std::cos;
  using std::sin;
  const V3<T> w(q[3], q[4], q[5]);
  const T c = cos(0.5 * q[kAlpha]), s = sin(0.5 * q[kAlpha]);
  const V3<T> b1 = lift<T>(frame_.col(0)), b2 = lift<T>(frame_.col(1)), n0 = lift<T>(frame_.col(2));
  e_a = rotate(w, c * b1 - s * b2) * q[kLengthA];
  e_b = rotate(w, c * b1 + s * b2) * q[kLengthB];
  n = rotate(w, n0);
}

template <class T>
TerminalEdge<T> Joint::terminal_edge(const T* q, int label, int sign, const SourceFrame& source,
                                     double theta_hint) const {
  using std::atan2;
  V3<T> e_a, e_b, n;
  geometry(q, e_a, e_b, n);
  const V3<T> e = (label == 0 ? e_a : e_b) * static_cast<double>(sign);
  const V3<T> p(q[0], q[1], q[2]);
  TerminalEdge<T> out;
  out.first = p - 0.5 * e;
  out.second = p + 0.5 * e;
  const Frame<T> ref = xshell::reference_frame<T>(e / norm(e), source);
  out.theta = unwrap_towards(atan2(-dot(n, ref.d1), dot(n, ref.d2)), theta_hint);
  return out;
}

}  // namespace xshell
