#include "joint.hpp"

#include <array>
#include <cmath>

namespace xshell {

bool nearly_parallel(const Eigen::Vector3d& e_a, const Eigen::Vector3d& e_b) {
  return e_a.cross(e_b).norm() <
         std::sin(kMinEdgeVectorAngleDegrees * M_PI / 180.0) * e_a.norm() * e_b.norm();
}

Joint::Joint(const Eigen::Vector3d& p, const Eigen::Vector3d& t_a, const Eigen::Vector3d& t_b,
             const Eigen::Vector3d& n, double l_a, double l_b, JointKind kind)
    : kind_(kind) {
  params_.segment<3>(kPosition) = p;
  if (kind == JointKind::EdgeVectors) {
    frame_.col(0) = t_a;
    frame_.col(1) = t_b;
    frame_.col(2) = n;
    params_.segment<3>(kEdgeA) = Eigen::Vector3d(l_a, 0.0, 0.0);
    params_.segment<3>(kEdgeB) = Eigen::Vector3d(l_b, 0.0, 0.0);
    return;
  }
  const double alpha = std::atan2(t_a.cross(t_b).dot(n), t_a.dot(t_b));
  // Bisector by rotating t_a half-way towards t_b: well defined for any alpha.
  const Eigen::Vector3d b1 = std::cos(0.5 * alpha) * t_a + std::sin(0.5 * alpha) * n.cross(t_a);
  frame_.col(0) = b1;
  frame_.col(1) = n.cross(b1);
  frame_.col(2) = n;
  params_.segment<3>(kOmega).setZero();
  params_[kAlpha] = alpha;
  params_[kLengthA] = l_a;
  params_[kLengthB] = l_b;
}

std::string Joint::check_params(const JointParams& params) const {
  if (!params.allFinite()) return "non-finite parameters";
  if (kind_ == JointKind::Rotation) {
    if (!(params[kLengthA] > 0.0 && params[kLengthB] > 0.0))
      return "terminal edge length must stay positive";
    return {};
  }
  const Eigen::Vector3d e_a = edge_basis(0) * params.segment<3>(kEdgeA);
  const Eigen::Vector3d e_b = edge_basis(1) * params.segment<3>(kEdgeB);
  if (!(e_a.norm() > 0.0 && e_b.norm() > 0.0)) return "terminal edge length must stay positive";
  if (nearly_parallel(e_a, e_b))
    return "edge vectors within " + std::to_string(kMinEdgeVectorAngleDegrees).substr(0, 3) +
           " degree of parallel (the normal e_A x e_B is ill-defined)";
  return {};
}

Eigen::Matrix3d Joint::edge_basis(int label) const {
  const Eigen::Vector3d t = frame_.col(label), n = frame_.col(2);
  Eigen::Matrix3d b;
  b << t, n.cross(t), n;
  return b;
}

double Joint::opening_angle() const {
  if (kind_ == JointKind::Rotation) return params_[kAlpha];
  const Eigen::Vector3d e_a = edge(0), e_b = edge(1);
  return std::atan2(e_a.cross(e_b).norm(), e_a.dot(e_b));
}

Eigen::Vector3d Joint::normal() const {
  if (kind_ == JointKind::Rotation)
    return rotation_matrix(params_.segment<3>(kOmega)) * frame_.col(2);
  V3<double> e_a, e_b, n;
  geometry(params_.data(), e_a, e_b, n);
  return n.values();
}

Eigen::Vector3d Joint::edge(int label) const {
  V3<double> e_a, e_b, n;
  geometry(params_.data(), e_a, e_b, n);
  return (label == 0 ? e_a : e_b).values();
}

void Joint::fold() {
  if (kind_ == JointKind::EdgeVectors) return;
  frame_ = rotation_matrix(params_.segment<3>(kOmega)) * frame_;
  params_.segment<3>(kOmega).setZero();
}

void Joint::align_reference_frame() {
  if (kind_ == JointKind::Rotation) return fold();
  V3<double> e_a, e_b, n;
  geometry(params_.data(), e_a, e_b, n);
  const double l_a = norm(e_a), l_b = norm(e_b);
  frame_.col(0) = e_a.values() / l_a;
  frame_.col(1) = e_b.values() / l_b;
  frame_.col(2) = n.values();
  params_.segment<3>(kEdgeA) = Eigen::Vector3d(l_a, 0.0, 0.0);
  params_.segment<3>(kEdgeB) = Eigen::Vector3d(l_b, 0.0, 0.0);
}

TerminalEdge<double> Joint::terminal_edge(int label, int sign, const SourceFrame& source,
                                          double theta_hint) const {
  return terminal_edge<double>(params_.data(), label, sign, source, theta_hint);
}

void Joint::terminal_edge_derivatives(int label, int sign, const SourceFrame& source,
                                      double theta_hint, Eigen::Matrix<double, 7, 9>& jacobian,
                                      JointHessian hessians[7]) const {
  using D = Dual<9>;
  std::array<D, 9> q;
  for (int i = 0; i < 9; ++i) q[i] = D::variable(i, params_[i]);
  const TerminalEdge<D> t = terminal_edge<D>(q.data(), label, sign, source, theta_hint);
  const D* out[7] = {&t.first.x,  &t.first.y,  &t.first.z, &t.second.x,
                     &t.second.y, &t.second.z, &t.theta};
  for (int k = 0; k < 7; ++k) {
    jacobian.row(k) = out[k]->g.transpose();
    hessians[k] = out[k]->h;
  }
}

}  // namespace xshell
