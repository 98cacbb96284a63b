#include "joint_derivatives.hpp"

#include <array>

#include "math/dual.hpp"
#include "math/dual1.hpp"
#include "math/inlining.hpp"
#include "math/rotation.hpp"

namespace xshell {

XSHELL_FLATTEN void terminal_edge_jacobian(const Joint& joint, int label, int sign,
                                           const SourceFrame& source, double theta_hint,
                                           Eigen::Matrix<double, 7, 9>& jacobian) {
  using D = Dual1<9>;
  D q[9];
  for (int i = 0; i < 9; ++i) q[i] = D::variable(i, joint.params()[i]);
  const TerminalEdge<D> t = joint.terminal_edge<D>(q, label, sign, source, theta_hint);
  const D* out[7] = {&t.first.x,  &t.first.y,  &t.first.z, &t.second.x,
                     &t.second.y, &t.second.z, &t.theta};
  for (int k = 0; k < 7; ++k) jacobian.row(k) = out[k]->g.transpose();
}

namespace {
// The joint's geometry v = (e_A, e_B, n) in forward-mode duals D seeded on
// parameters 3..8 (p enters as a constant).
template <class D>
std::array<D, 9> joint_geometry_duals(const Joint& joint) {
  D q[9];
  for (int i = 0; i < 3; ++i) q[i] = D(joint.params()[i]);
  for (int i = 3; i < 9; ++i) q[i] = D::variable(i - 3, joint.params()[i]);
  V3<D> e_a, e_b, n;
  joint.geometry<D>(q, e_a, e_b, n);
  return {e_a.x, e_a.y, e_a.z, e_b.x, e_b.y, e_b.z, n.x, n.y, n.z};
}
}  // namespace

XSHELL_FLATTEN void joint_geometry_derivatives_by_ad(const Joint& joint,
                                                     JointGeometryDerivatives& out) {
  const std::array<Dual<6>, 9> v = joint_geometry_duals<Dual<6>>(joint);
  for (int k = 0; k < 9; ++k) {
    out.value[k] = v[k].v;
    out.jacobian.row(k) = v[k].g.transpose();
    out.hessians[k] = v[k].h;
  }
}

namespace {
// Rotation joints (joint.hpp): with c = cos(alpha/2), s = sin(alpha/2),
//   e_A = l_A R(w) (c b1 - s b2),  e_B = l_B R(w) (c b1 + s b2),  n = R(w) n0,
// so R(w) b1, R(w) b2, R(w) n0 by second-order AD over w alone (Dual<3>)
// give everything; the alpha and length derivatives are written out.
// Local parameter order: w (0-2), alpha (3), l_A (4), l_B (5).
XSHELL_FLATTEN void rotation_joint_geometry_derivatives(const Joint& joint,
                                                        JointGeometryDerivatives& out) {
  using D = Dual<3>;
  const JointParams& q = joint.params();
  const V3<D> w(D::variable(0, q[kOmega]), D::variable(1, q[kOmega + 1]),
                D::variable(2, q[kOmega + 2]));
  const Eigen::Matrix3d& frame = joint.reference_frame();
  V3<D> rotated[3];
  for (int k = 0; k < 3; ++k) rotated[k] = rotate(w, lift<D>(frame.col(k)));
  const D* r1[3] = {&rotated[0].x, &rotated[0].y, &rotated[0].z};
  const D* r2[3] = {&rotated[1].x, &rotated[1].y, &rotated[1].z};
  const D* rn[3] = {&rotated[2].x, &rotated[2].y, &rotated[2].z};
  const double c = std::cos(0.5 * q[kAlpha]), s = std::sin(0.5 * q[kAlpha]);
  for (int label = 0; label < 2; ++label) {
    const double sign = label == 0 ? -1.0 : 1.0;
    const double l = q[kLengthA + label];
    const int li = 4 + label;  // local index of l_X
    // u = a r1 + b r2 and its alpha derivatives.
    const double a = c, b = sign * s, da = -0.5 * s, db = 0.5 * sign * c, dda = -0.25 * c,
                 ddb = -0.25 * sign * s;
    for (int k = 0; k < 3; ++k) {
      const D& p = *r1[k];
      const D& m = *r2[k];
      const int row = 3 * label + k;
      const double u = a * p.v + b * m.v, du = da * p.v + db * m.v;
      const Eigen::Vector3d gu = a * p.g + b * m.g, gdu = da * p.g + db * m.g;
      out.value[row] = l * u;
      out.jacobian.row(row).setZero();
      out.jacobian.block<1, 3>(row, 0) = l * gu.transpose();
      out.jacobian(row, 3) = l * du;
      out.jacobian(row, li) = u;
      Eigen::Matrix<double, 6, 6>& h = out.hessians[row];
      h.setZero();
      const Eigen::Matrix3d hw = l * (a * p.h + b * m.h);
      h.block<3, 3>(0, 0) = 0.5 * (hw + hw.transpose());  // symmetric bit for bit
      h.block<3, 1>(0, 3) = l * gdu;
      h.block<3, 1>(0, li) = gu;
      h(3, 3) = l * (dda * p.v + ddb * m.v);
      h(3, li) = du;
      h.block<1, 3>(3, 0) = h.block<3, 1>(0, 3).transpose();
      h.block<1, 3>(li, 0) = h.block<3, 1>(0, li).transpose();
      h(li, 3) = du;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const D& n = *rn[k];
    out.value[6 + k] = n.v;
    out.jacobian.row(6 + k).setZero();
    out.jacobian.block<1, 3>(6 + k, 0) = n.g.transpose();
    out.hessians[6 + k].setZero();
    out.hessians[6 + k].block<3, 3>(0, 0) = 0.5 * (n.h + n.h.transpose());
  }
}
}  // namespace

void joint_geometry_derivatives(const Joint& joint, JointGeometryDerivatives& out) {
  if (joint.kind() == JointKind::Rotation)
    rotation_joint_geometry_derivatives(joint, out);
  else
    joint_geometry_derivatives_by_ad(joint, out);
}

XSHELL_FLATTEN void joint_geometry_jacobian(const Joint& joint, JointGeometryDerivatives& out) {
  const std::array<Dual1<6>, 9> v = joint_geometry_duals<Dual1<6>>(joint);
  for (int k = 0; k < 9; ++k) {
    out.value[k] = v[k].v;
    out.jacobian.row(k) = v[k].g.transpose();
  }
}

namespace {
// dtheta/de and dtheta/dn of a terminal edge's theta (see the header).
template <class T>
void theta_gradient(const V3<T>& e, const V3<T>& n, const SourceFrame& source, V3<T>& ge,
                    V3<T>& gn) {
  const T l = norm(e);
  const V3<T> t = e * (1.0 / l);
  Frame<T> ref;
  V3<T> kh;
  detail::transported_frame(t, source, ref, kh);
  const T y = -dot(n, ref.d1), x = dot(n, ref.d2);
  const V3<T> u = (ref.d1 * x + ref.d2 * y) * (1.0 / (x * x + y * y));
  gn = -u;
  const V3<T> g = u * dot(n, t) + kh * 0.5;
  ge = (g - t * dot(g, t)) * (1.0 / l);
}
}  // namespace

namespace {

// Rows 0-5 of a terminal edge's Jacobian: the nodes p -/+ (s/2) e_X.
void node_jacobian(const JointGeometryDerivatives& geometry, int e0, double s,
                   Eigen::Matrix<double, 7, 9>& jacobian) {
  jacobian.setZero();
  for (int c = 0; c < 3; ++c) {
    jacobian(c, c) = 1.0;
    jacobian(3 + c, c) = 1.0;
    jacobian.block<1, 6>(c, 3) = (-0.5 * s) * geometry.jacobian.row(e0 + c);
    jacobian.block<1, 6>(3 + c, 3) = (0.5 * s) * geometry.jacobian.row(e0 + c);
  }
}

// d u / d params[3..8] for u = (s e_X, n).
Eigen::Matrix<double, 6, 6> edge_and_normal_jacobian(const JointGeometryDerivatives& geometry,
                                                     int e0, double s) {
  Eigen::Matrix<double, 6, 6> ju;
  for (int c = 0; c < 3; ++c) {
    ju.row(c) = s * geometry.jacobian.row(e0 + c);
    ju.row(3 + c) = geometry.jacobian.row(6 + c);
  }
  return ju;
}

}  // namespace

XSHELL_FLATTEN void terminal_edge_jacobian(const JointGeometryDerivatives& geometry, int label,
                                           int sign, const SourceFrame& source,
                                           Eigen::Matrix<double, 7, 9>& jacobian) {
  const double s = static_cast<double>(sign);
  const int e0 = 3 * label;
  node_jacobian(geometry, e0, s, jacobian);
  const V3<double> e(s * geometry.value[e0], s * geometry.value[e0 + 1],
                     s * geometry.value[e0 + 2]);
  const V3<double> n(geometry.value[6], geometry.value[7], geometry.value[8]);
  V3<double> ge, gn;
  theta_gradient(e, n, source, ge, gn);
  const Eigen::Matrix<double, 6, 1> g(ge.x, ge.y, ge.z, gn.x, gn.y, gn.z);
  jacobian.block<1, 6>(6, 3) = g.transpose() * edge_and_normal_jacobian(geometry, e0, s);
}

XSHELL_FLATTEN void terminal_edge_derivatives(const JointGeometryDerivatives& geometry, int label,
                                              int sign, const SourceFrame& source,
                                              TerminalEdgeDerivatives& out) {
  const double s = static_cast<double>(sign);
  const int e0 = 3 * label;  // rows of e_X in the geometry
  node_jacobian(geometry, e0, s, out.jacobian);
  for (int c = 0; c < 3; ++c) {
    out.hessians[c] = (-0.5 * s) * geometry.hessians[e0 + c];
    out.hessians[3 + c] = (0.5 * s) * geometry.hessians[e0 + c];
  }
  // theta(u), u = (s e_X, n): gradient in closed form, Hessian as its
  // Jacobian, both chained through the geometry.
  using D = Dual1<6>;
  const V3<D> e(D::variable(0, s * geometry.value[e0]), D::variable(1, s * geometry.value[e0 + 1]),
                D::variable(2, s * geometry.value[e0 + 2]));
  const V3<D> n(D::variable(3, geometry.value[6]), D::variable(4, geometry.value[7]),
                D::variable(5, geometry.value[8]));
  V3<D> ge, gn;
  theta_gradient(e, n, source, ge, gn);
  const D* gu[6] = {&ge.x, &ge.y, &ge.z, &gn.x, &gn.y, &gn.z};
  Eigen::Matrix<double, 6, 1> g;
  Eigen::Matrix<double, 6, 6> h;
  for (int k = 0; k < 6; ++k) {
    g[k] = gu[k]->v;
    h.row(k) = gu[k]->g.transpose();
  }
  const Eigen::Matrix<double, 6, 6> hu = 0.5 * (h + h.transpose());
  const Eigen::Matrix<double, 6, 6> ju = edge_and_normal_jacobian(geometry, e0, s);
  out.jacobian.block<1, 6>(6, 3) = g.transpose() * ju;
  Eigen::Matrix<double, 6, 6> ht = ju.transpose() * hu * ju;
  for (int c = 0; c < 3; ++c) {
    ht += (g[c] * s) * geometry.hessians[e0 + c];
    ht += g[3 + c] * geometry.hessians[6 + c];
  }
  out.hessians[6] = 0.5 * (ht + ht.transpose());
}

}  // namespace xshell
