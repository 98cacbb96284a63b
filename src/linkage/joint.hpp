// A scissor joint, in one of two parametrizations (docs/model.md section 5), both with 9 parameters
// and the same map to the terminal edges of its segments.
//
// JointKind::Rotation (docs/model.md section 5.2), with a bisector frame. Parameters: position p
// (3), rotation vector omega (3), opening angle alpha, and the lengths l_A, l_B of the two terminal
// edges. The joint stores a reference frame R0 = [b1 b2 n0]: the bisector b1 of the two rods'
// tangents, b2 = n0 x b1, and the normal n0. Then
//   t_A = R(omega) R0 (cos(alpha/2), -sin(alpha/2), 0)
//   t_B = R(omega) R0 (cos(alpha/2),  sin(alpha/2), 0)
//   e_A = l_A t_A,  e_B = l_B t_B,  n = R(omega) n0,
// so alpha is the angle from t_A to t_B about n, in (0, pi), and the two rods open symmetrically
// about the bisector. Fixing omega ("orientation") holds the bisector and the normal still while
// alpha stays free. After a fold (R0 <- R(omega) R0, omega <- 0) the configuration is the same and
// omega sits at 0, where rotation.hpp evaluates R exactly.
//
// JointKind::EdgeVectors (docs/model.md section 5.4): the edge vectors themselves. Parameters:
// position p (3), then e_A (3) and e_B (3), each expressed in a fixed orthonormal basis of its own
// rod,
//   e_A = B_A c_A,  B_A = [t0_A, n0 x t0_A, n0],
//   e_B = B_B c_B,  B_B = [t0_B, n0 x t0_B, n0],
//   n = e_A x e_B / |e_A x e_B|,
// where the reference frame stores the columns [t0_A t0_B n0] (the rods' directions and the normal
// when the basis was last aligned, usually at construction). Component 0 of c_X is the length along
// t0_X, 1 the in-plane and 2 the out-of-plane deviation. A fixed orthogonal change of variables
// from global edge vectors (e_A, e_B), so it changes neither the energy landscape nor the
// solutions; it makes the constrained joint (docs/model.md section 8.1: fixed directions, free
// lengths) a matter of fixing c_A[1..2] and c_B[1..2] at 0 right after align_reference_frame()
// (statics_problem.hpp does so for a support "orientation"). There is no rotation to fold: fold()
// does nothing. The normal is ill-defined where e_A and e_B are parallel: configurations with |e_A
// x e_B| < sin(kMinEdgeVectorAngleDegrees) |e_A| |e_B| are refused (check_params).
//
// Either way, the joint sets the terminal edge of every incident segment:
// the edge sign * e_X is centred on p (nodes p -/+ sign * e_X / 2), and its
// material frame has d2 = n, which fixes the edge's theta relative to its
// reference frame (frames.hpp): theta = atan2(-n . d1_ref, n . d2_ref), on
// the branch nearest the previous value.
#pragma once

#include <Eigen/Core>
#include <string>

#include "math/rotation.hpp"
#include "rod/frames.hpp"
#include "rod/vertex_stencil.hpp"

namespace xshell {

using JointParams = Eigen::Matrix<double, 9, 1>;
using JointGradient = Eigen::Matrix<double, 9, 1>;
using JointHessian = Eigen::Matrix<double, 9, 9>;

enum class JointKind { Rotation, EdgeVectors };

// Parameter offsets. Rotation joints: p, omega, alpha, l_A, l_B.
enum JointParam { kPosition = 0, kOmega = 3, kAlpha = 6, kLengthA = 7, kLengthB = 8 };
// Edge-vector joints: p, c_A, c_B (components in the bases B_A, B_B).
enum EdgeVectorParam { kEdgeA = 3, kEdgeB = 6 };

// Edge-vector joints refuse rods closer than this to parallel (or
// antiparallel): their normal e_A x e_B / |e_A x e_B| would turn by
// 1 / sin(angle) radians per radian that an edge turns.
constexpr double kMinEdgeVectorAngleDegrees = 1.0;

// True when |e_a x e_b| < sin(kMinEdgeVectorAngleDegrees) |e_a| |e_b|.
bool nearly_parallel(const Eigen::Vector3d& e_a, const Eigen::Vector3d& e_b);

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
        const Eigen::Vector3d& n, double l_a, double l_b, JointKind kind = JointKind::Rotation);

  JointKind kind() const { return kind_; }
  const JointParams& params() const { return params_; }
  void set_params(const JointParams& params) { params_ = params; }
  // Rotation: [b1 b2 n0]; edge vectors: [t0_A t0_B n0] (see above).
  const Eigen::Matrix3d& reference_frame() const { return frame_; }
  void set_reference_frame(const Eigen::Matrix3d& frame) { frame_ = frame; }

  // Empty when the parameters are admissible for this joint, else why not
  // (non-finite values, a non-positive length, nearly parallel edges).
  std::string check_params(const JointParams& params) const;

  Eigen::Vector3d position() const { return params_.segment<3>(kPosition); }
  // Angle between t_A and t_B, in (0, pi).
  double opening_angle() const;
  Eigen::Vector3d normal() const;
  // Edge vector e_X and unit tangent t_X of rod `label` (0: A, 1: B).
  Eigen::Vector3d edge(int label) const;
  Eigen::Vector3d tangent(int label) const { return edge(label).normalized(); }

  // Rotation: folds omega into the reference frame. Edge vectors: nothing.
  // The geometry is unchanged.
  void fold();
  // Rotation: fold(). Edge vectors: the bases are re-aligned with the
  // current directions, so that c_A = (l_A, 0, 0), c_B = (l_B, 0, 0). The
  // geometry is unchanged.
  void align_reference_frame();

  // Edge vectors and normal as functions of the parameters.
  template <class T>
  void geometry(const T* q, V3<T>& e_a, V3<T>& e_b, V3<T>& n) const;

  template <class T>
  TerminalEdge<T> terminal_edge(const T* q, int label, int sign, const SourceFrame& source,
                                double theta_hint) const;

  // The terminal edge at the current parameters, and its exact first and
  // second derivatives: jacobian (7 x 9) and one 9 x 9 Hessian per value.
  TerminalEdge<double> terminal_edge(int label, int sign, const SourceFrame& source,
                                     double theta_hint) const;
  void terminal_edge_derivatives(int label, int sign, const SourceFrame& source, double theta_hint,
                                 Eigen::Matrix<double, 7, 9>& jacobian,
                                 JointHessian hessians[7]) const;

  // Edge-vector joints: the basis B_X (columns as above) of rod `label`.
  Eigen::Matrix3d edge_basis(int label) const;

 private:
  JointKind kind_ = JointKind::Rotation;
  JointParams params_ = JointParams::Zero();
  Eigen::Matrix3d frame_ = Eigen::Matrix3d::Identity();
};

template <class T>
void Joint::geometry(const T* q, V3<T>& e_a, V3<T>& e_b, V3<T>& n) const {
  using std::cos;
  using std::sin;
  if (kind_ == JointKind::EdgeVectors) {
    const auto in_basis = [&](int label, const T* c) {
      const Eigen::Matrix3d b = edge_basis(label);
      return lift<T>(b.col(0)) * c[0] + lift<T>(b.col(1)) * c[1] + lift<T>(b.col(2)) * c[2];
    };
    e_a = in_basis(0, q + kEdgeA);
    e_b = in_basis(1, q + kEdgeB);
    const V3<T> c = cross(e_a, e_b);
    n = c / norm(c);
    return;
  }
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
