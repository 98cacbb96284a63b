#include "joint.hpp"

#include <array>

namespace xshell {

Joint::Joint(const Eigen::Vector3d& p, const Eigen::Vector3d& t_a, const Eigen::Vector3d& t_b,
             const Eigen::Vector3d& n, double l_a, double l_b) {
  const double alpha = std::atan2(t_a.cross(t_b).dot(n), t_a.dot(t_b));
  // Bisector by rotating t_a half-way towards t_b: well defined for any alpha.
  const Eigen::Vector3d b1 = std::cos(0.5 * alpha) * t_a + std::sin(0.5 * alpha) * n.cross(t_a);
  frame_.col(0) = b1;
  frame_.col(1) = n.cross(b1);
  frame_.col(2) = n;
  params_.segment<3>(kPosition) = p;
  params_.segment<3>(kOmega).setZero();
  params_[kAlpha] = alpha;
  params_[kLengthA] = l_a;
  params_[kLengthB] = l_b;
}

Eigen::Vector3d Joint::normal() const {
  return rotation_matrix(params_.segment<3>(kOmega)) * frame_.col(2);
}

Eigen::Vector3d Joint::tangent(int label) const {
  V3<double> e_a, e_b, n;
  geometry(params_.data(), e_a, e_b, n);
  return (label == 0 ? e_a : e_b).values().normalized();
}

void Joint::fold() {
  frame_ = rotation_matrix(params_.segment<3>(kOmega)) * frame_;
  params_.segment<3>(kOmega).setZero();
}

TerminalEdge<double> Joint::terminal_edge(int label, int sign, const SourceFrame& source,
                                          double theta_hint) const {
  return terminal_edge<double>(params_.data(), label, sign, source, theta_hint);
}

void Joint::terminal_edge_derivatives(int label, int sign, const SourceFrame& source, double theta_hint,
                                      Eigen::Matrix<double, 7, 9>& jacobian, JointHessian hessians[7]) const {
  using D = Dual<9>;
  std::array<D, 9> q;
  for (int i = 0; i < 9; ++i) q[i] = D::variable(i, params_[i]);
  const TerminalEdge<D> t = terminal_edge<D>(q.data(), label, sign, source, theta_hint);
  const D* out[7] = {&t.first.x, &t.first.y, &t.first.z, &t.second.x, &t.second.y, &t.second.z, &t.theta};
  for (int k = 0; k < 7; ++k) {
    jacobian.row(k) = out[k]->g.transpose();
    hessians[k] = out[k]->h;
  }
}

}  // namespace xshell
