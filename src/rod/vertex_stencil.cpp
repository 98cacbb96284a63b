#include "vertex_stencil.hpp"

namespace xshell {

namespace {
template <class T>
VertexStrains<T> strains_of(const std::array<T, 11>& q, const VertexStencil& s) {
  const V3<T> x0(q[0], q[1], q[2]), x1(q[3], q[4], q[5]), x2(q[6], q[7], q[8]);
  return vertex_strains(x0, x1, x2, q[9], q[10], s);
}

template <class T>
void scatter_gradient(const VertexEdgeGradient<T>& d, VertexGradient& gradient) {
  for (int c = 0; c < 3; ++c) {
    const double g0 = value(c == 0 ? d.e[0].x : c == 1 ? d.e[0].y : d.e[0].z);
    const double g1 = value(c == 0 ? d.e[1].x : c == 1 ? d.e[1].y : d.e[1].z);
    gradient[c] = -g0;
    gradient[3 + c] = g0 - g1;
    gradient[6 + c] = g1;
  }
  gradient[9] = value(d.theta[0]);
  gradient[10] = value(d.theta[1]);
}

std::array<double, 11> to_array(const VertexDofs& q) {
  std::array<double, 11> a;
  for (int i = 0; i < 11; ++i) a[i] = q[i];
  return a;
}
}  // namespace

VertexStrains<double> vertex_strains(const VertexDofs& q, const VertexStencil& s) {
  return strains_of<double>(to_array(q), s);
}

XSHELL_FLATTEN VertexEnergy<double> vertex_energy(const VertexDofs& q, const VertexStencil& s) {
  return vertex_energy(strains_of<double>(to_array(q), s), s);
}

VertexEnergy<double> vertex_energy_derivatives(const VertexDofs& q, const VertexStencil& s,
                                               VertexGradient& gradient, VertexHessian& hessian) {
  using D = Dual<11>;
  std::array<D, 11> qd;
  for (int i = 0; i < 11; ++i) qd[i] = D::variable(i, q[i]);
  const VertexEnergy<D> e = vertex_energy(strains_of<D>(qd, s), s);
  const D total = e.bending + e.twisting;
  gradient = total.g;
  hessian = total.h;
  return {e.bending.v, e.twisting.v};
}

XSHELL_FLATTEN VertexEnergy<double> vertex_energy_gradient(const VertexDofs& q,
                                                           const VertexStencil& s,
                                                           VertexGradient& gradient) {
  const V3<double> x0(q[0], q[1], q[2]), x1(q[3], q[4], q[5]), x2(q[6], q[7], q[8]);
  const VertexEdgeGradient<double> d = vertex_edge_gradient(x1 - x0, x2 - x1, q[9], q[10], s);
  scatter_gradient(d, gradient);
  return {d.bending, d.twisting};
}

XSHELL_FLATTEN VertexEnergy<double> vertex_energy_hessian(const VertexDofs& q,
                                                          const VertexStencil& s,
                                                          VertexGradient& gradient,
                                                          VertexHessian& hessian) {
  using D = Dual1<8>;
  const V3<D> e0(D::variable(0, q[3] - q[0]), D::variable(1, q[4] - q[1]),
                 D::variable(2, q[5] - q[2]));
  const V3<D> e1(D::variable(3, q[6] - q[3]), D::variable(4, q[7] - q[4]),
                 D::variable(5, q[8] - q[5]));
  const VertexEdgeGradient<D> d =
      vertex_edge_gradient(e0, e1, D::variable(6, q[9]), D::variable(7, q[10]), s);
  scatter_gradient(d, gradient);
  Eigen::Matrix<double, 8, 8> h;
  h.row(0) = d.e[0].x.g.transpose();
  h.row(1) = d.e[0].y.g.transpose();
  h.row(2) = d.e[0].z.g.transpose();
  h.row(3) = d.e[1].x.g.transpose();
  h.row(4) = d.e[1].y.g.transpose();
  h.row(5) = d.e[1].z.g.transpose();
  h.row(6) = d.theta[0].g.transpose();
  h.row(7) = d.theta[1].g.transpose();
  const Eigen::Matrix<double, 8, 8> sym = 0.5 * (h + h.transpose());
  // e0 = x1 - x0, e1 = x2 - x1: H_q = M^T sym M, written out by blocks.
  const Eigen::Matrix3d a = sym.block<3, 3>(0, 0), b = sym.block<3, 3>(0, 3),
                        c = sym.block<3, 3>(3, 3);
  const Eigen::Matrix<double, 3, 2> ta = sym.block<3, 2>(0, 6), tb = sym.block<3, 2>(3, 6);
  hessian.block<3, 3>(0, 0) = a;
  hessian.block<3, 3>(0, 3) = b - a;
  hessian.block<3, 3>(0, 6) = -b;
  const Eigen::Matrix3d middle = a + c - b - b.transpose();
  hessian.block<3, 3>(3, 3) = 0.5 * (middle + middle.transpose());  // symmetric bit for bit
  hessian.block<3, 3>(3, 6) = b - c;
  hessian.block<3, 3>(6, 6) = c;
  hessian.block<3, 2>(0, 9) = -ta;
  hessian.block<3, 2>(3, 9) = ta - tb;
  hessian.block<3, 2>(6, 9) = tb;
  hessian.block<2, 2>(9, 9) = sym.block<2, 2>(6, 6);
  hessian.block<3, 3>(3, 0) = hessian.block<3, 3>(0, 3).transpose();
  hessian.block<3, 3>(6, 0) = hessian.block<3, 3>(0, 6).transpose();
  hessian.block<3, 3>(6, 3) = hessian.block<3, 3>(3, 6).transpose();
  hessian.block<2, 9>(9, 0) = hessian.block<9, 2>(0, 9).transpose();
  return {d.bending.v, d.twisting.v};
}

}  // namespace xshell
