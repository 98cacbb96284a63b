#include "edge_vector_theta.hpp"

namespace xshell {

namespace {
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return k;
}

struct EdgeGeometry {
  Eigen::Vector3d t;  // t^j
  Eigen::Vector3d n;  // joint normal
  double cross_norm;  // |e_A x e_B|
};

EdgeGeometry edge_geometry(const EdgeVectorThetaStencil& s) {
  const Eigen::Vector3d c = s.e_a.cross(s.e_b);
  const Eigen::Vector3d& e = s.label == 0 ? s.e_a : s.e_b;
  return {s.sign * e.normalized(), c.normalized(), c.norm()};
}
}  // namespace

Eigen::Matrix<double, 6, 6> EdgeVectorThetaHessian::full() const {
  Eigen::Matrix<double, 6, 6> h;
  h << aa, ab, ab.transpose(), bb;
  return h;
}

Eigen::Vector3d transport_turn_gradient(const Eigen::Vector3d& t, const SourceFrame& source) {
  const Eigen::Vector3d& t_hat = source.tangent;
  const Eigen::Vector3d& d1_hat = source.d1;
  const Frame<double> ref = reference_frame<double>(V3<double>(t), source);
  const Eigen::Vector3d d1 = ref.d1.values(), d2 = ref.d2.values();
  const double chi = 1.0 + t_hat.dot(t);
  return ((d1_hat.dot(t)) * d1.cross(t_hat) + d2.dot(t_hat) * d1_hat) / chi -
         (d1_hat.dot(t)) * d2.dot(t_hat) / (chi * chi) * t_hat + d1_hat.cross(d1);
}

Eigen::Matrix<double, 6, 1> edge_vector_theta_gradient(const EdgeVectorThetaStencil& s) {
  const EdgeGeometry g = edge_geometry(s);
  Eigen::Matrix<double, 6, 1> out;
  // Rotation of the normal, d2 = n.
  out.head<3>() = -g.t.dot(s.e_b) / g.cross_norm * g.n;
  out.tail<3>() = g.t.dot(s.e_a) / g.cross_norm * g.n;
  // Minus the turn of the reference frame by parallel transport.
  const Eigen::Vector3d& e = s.label == 0 ? s.e_a : s.e_b;
  const Eigen::Vector3d t_x = e.normalized();
  const Eigen::Matrix3d project = (Eigen::Matrix3d::Identity() - t_x * t_x.transpose()) / e.norm();
  out.segment<3>(3 * s.label) += s.sign * project * transport_turn_gradient(g.t, s.source);
  return out;
}

EdgeVectorThetaHessian edge_vector_theta_hessian(const EdgeVectorThetaStencil& s) {
  const EdgeGeometry g = edge_geometry(s);
  const Eigen::Vector3d d2 = g.n, d1 = g.n.cross(g.t);
  const Eigen::Matrix3d reflect = Eigen::Matrix3d::Identity() - 2.0 * g.n * g.n.transpose();
  const Eigen::Matrix3d sym = d2 * d1.transpose() + d1 * d2.transpose();
  const double c2 = g.cross_norm * g.cross_norm;
  EdgeVectorThetaHessian h;
  h.aa = g.t.dot(s.e_b) / c2 * reflect * cross_matrix(s.e_b);
  h.bb = g.t.dot(s.e_a) / c2 * reflect * cross_matrix(s.e_a);
  if (s.label == 0)
    h.aa -= sym / (2.0 * s.e_a.squaredNorm());
  else
    h.bb -= sym / (2.0 * s.e_b.squaredNorm());
  h.ab =
      -g.n * g.t.transpose() / g.cross_norm - g.t.dot(s.e_b) / c2 * reflect * cross_matrix(s.e_a);
  return h;
}

}  // namespace xshell
