#include "vertex_stencil.hpp"

namespace xshell {

namespace {
template <class T>
VertexStrains<T> strains_of(const std::array<T, 11>& q, const VertexStencil& s) {
  const V3<T> x0(q[0], q[1], q[2]), x1(q[3], q[4], q[5]), x2(q[6], q[7], q[8]);
  return vertex_strains(x0, x1, x2, q[9], q[10], s);
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

VertexEnergy<double> vertex_energy(const VertexDofs& q, const VertexStencil& s) {
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

}  // namespace xshell
