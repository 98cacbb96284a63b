// Bending and twisting of a discrete elastic rod at one interior vertex i,
// over its stencil of 11 unknowns (Bergou et al. 2008, 2010):
//   q = (x_{i-1}, x_i, x_{i+1}, theta_{i-1}, theta_i).
//
// Curvature binormal (the discrete curvature we use):
//   kb = 2 e0 x e1 / (|e0| |e1| + e0 . e1),  e0 = x_i - x_{i-1}, e1 = x_{i+1} - x_i,
// of length 2 tan(phi/2) for a turning angle phi. Material curvatures are
// taken in the material frame of each of the two edges, j in {0, 1}:
//   kappa1^j = kb . d2^j,  kappa2^j = -kb . d1^j,
// and the bending energy averages the two (as in Bergou et al. 2010):
//   E_bend = 1/(2V) * 1/2 sum_j [B1 (kappa1^j - kappa1_rest^j)^2 + B2 (kappa2^j - kappa2_rest^j)^2]
// with V = (l0_rest + l1_rest)/2 the vertex's Voronoi length. Evaluating the
// curvature in each edge's own frame (rather than in an averaged frame) keeps
// the energy exact for anisotropic sections when theta jumps between edges
// and makes rest curvatures of either edge independent.
// Twist: m = theta_i - theta_{i-1} + m_ref, with m_ref the reference twist,
// the signed angle about t1 from P_{t0}^{t1} d1_ref^0 to d1_ref^1 (unwrapped
// by multiples of 2 pi towards a hint, its value at the last update):
//   E_twist = GJ / (2V) (m - m_rest)^2.
// The reference frames are time-parallel transported from each edge's source
// frame (frames.hpp), so value, gradient and Hessian below are exact at every
// configuration, not only right after a source-frame update: they are
// computed by forward-mode automatic differentiation (math/dual.hpp) of the
// formulas above.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "frames.hpp"
#include "math/dual1.hpp"

namespace xshell {

struct VertexStencil {
  SourceFrame source[2];                                  // source frames of edges i-1 and i
  double rest_kappa[2][2] = {};                           // [edge j][kappa1, kappa2] at rest
  double rest_twist = 0.0;                                // m_rest
  double twist_hint = 0.0;                                // reference twist at the last update
  double voronoi_length = 1.0;                            // V
  double bending1 = 0.0, bending2 = 0.0, twisting = 0.0;  // B1, B2, GJ
};

using VertexDofs = Eigen::Matrix<double, 11, 1>;
using VertexGradient = Eigen::Matrix<double, 11, 1>;
using VertexHessian = Eigen::Matrix<double, 11, 11>;

// Strains at the vertex.
template <class T>
struct VertexStrains {
  V3<T> kb;
  T kappa[2][2];  // [edge j][kappa1, kappa2]
  T twist;        // m (material twist, including theta)
  T reference_twist;
};

template <class T>
T unwrap_towards(const T& angle, double hint) {
  const double two_pi = 2.0 * M_PI;
  return angle + two_pi * std::round((hint - value(angle)) / two_pi);
}

template <class T>
VertexStrains<T> vertex_strains(const V3<T>& x0, const V3<T>& x1, const V3<T>& x2, const T& theta0,
                                const T& theta1, const VertexStencil& s) {
  const V3<T> e0 = x1 - x0, e1 = x2 - x1;
  const T l0 = norm(e0), l1 = norm(e1);
  const V3<T> t0 = e0 / l0, t1 = e1 / l1;
  VertexStrains<T> out;
  out.kb = (2.0 * cross(e0, e1)) / (l0 * l1 + dot(e0, e1));
  const Frame<T> ref0 = reference_frame(t0, s.source[0]);
  const Frame<T> ref1 = reference_frame(t1, s.source[1]);
  const Frame<T> mat[2] = {material_frame(ref0, theta0), material_frame(ref1, theta1)};
  for (int j = 0; j < 2; ++j) {
    out.kappa[j][0] = dot(out.kb, mat[j].d2);
    out.kappa[j][1] = -dot(out.kb, mat[j].d1);
  }
  out.reference_twist =
      unwrap_towards(signed_angle(parallel_transport(t0, t1, ref0.d1), ref1.d1, t1), s.twist_hint);
  out.twist = theta1 - theta0 + out.reference_twist;
  return out;
}

template <class T>
struct VertexEnergy {
  T bending, twisting;
};

template <class T>
VertexEnergy<T> vertex_energy(const VertexStrains<T>& k, const VertexStencil& s) {
  VertexEnergy<T> e{T(0.0), T(0.0)};
  for (int j = 0; j < 2; ++j) {
    const T a = k.kappa[j][0] - s.rest_kappa[j][0];
    const T b = k.kappa[j][1] - s.rest_kappa[j][1];
    e.bending += s.bending1 * a * a + s.bending2 * b * b;
  }
  e.bending = e.bending * (0.25 / s.voronoi_length);
  const T m = k.twist - s.rest_twist;
  e.twisting = (0.5 * s.twisting / s.voronoi_length) * m * m;
  return e;
}

// Closed-form gradient of E_bend + E_twist with respect to the edge vectors
// e0 = x_i - x_{i-1}, e1 = x_{i+1} - x_i and the two thetas, exact at every
// configuration (any source frames). With t_j = e_j/|e_j|, a variation of
// edge j turns its material frame by the angular velocity
//   omega_j = t_j x dt_j + (dtheta_j + psi_j) t_j,  dt_j = (I - t_j t_j^T) de_j / |e_j|,
// where psi_j is the twist that the time-parallel transport from the source
// tangent t^_j adds (the holonomy of the spherical triangle t^_j, t_j,
// t_j + dt_j):
//   psi_j = -(kh_j / 2) . dt_j,  kh_j = 2 t^_j x t_j / (1 + t^_j . t_j).
// So d d1_j = -t_j (d1_j . dt_j) + (dtheta_j + psi_j) d2_j and
// d d2_j = -t_j (d2_j . dt_j) - (dtheta_j + psi_j) d1_j; since kb . t_j = 0,
//   d kappa1^j = dkb . d2_j + (dtheta_j + psi_j) kappa2^j,
//   d kappa2^j = -dkb . d1_j - (dtheta_j + psi_j) kappa1^j,
//   d m_ref = psi_1 - psi_0 + (kb / 2) . (dt_0 + dt_1)   (Bergou et al. 2010,
//     plus the psi_j terms, which vanish right after a source-frame update),
//   kb = 2 t0 x t1 / chi, chi = 1 + t0 . t1:
//   d (kb . W) = (2/chi) [dt0 . (t1 x W) + dt1 . (W x t0)] - (kb . W / chi)(t1 . dt0 + t0 . dt1).
// With f_j = B1 (kappa1^j - rest) / (2V), g_j = B2 (kappa2^j - rest) / (2V),
// h = GJ (m - m_rest) / V, W = sum_j (f_j d2_j - g_j d1_j) and
// rho_j = f_j kappa2^j - g_j kappa1^j:
//   dE/dtheta_0 = rho_0 - h,  dE/dtheta_1 = rho_1 + h,
//   dE/dt_0 = (2 t1 x W - (kb . W) t1) / chi - (dE/dtheta_0) kh_0 / 2 + h kb / 2,
//   dE/dt_1 = (2 W x t0 - (kb . W) t0) / chi - (dE/dtheta_1) kh_1 / 2 + h kb / 2,
//   dE/de_j = (I - t_j t_j^T) dE/dt_j / |e_j|.
// Written over any scalar: with Dual1<8> seeded on (e0, e1, theta0,
// theta1) it gives the exact Hessian as the Jacobian of this gradient.
template <class T>
struct VertexEdgeGradient {
  V3<T> e[2];           // dE/de_0, dE/de_1
  T theta[2];           // dE/dtheta_0, dE/dtheta_1
  T bending, twisting;  // energies
};

namespace detail {

// The reference frame of an edge of unit tangent t transported from its
// (constant) source frame, P_{t^}^{t} d1^ = (t^.t) d1^ + c x d1^ + (c.d1^)/(1 + t^.t) c
// with c = t^ x t (frames.hpp), and kh = 2 c / (1 + t^.t); constants are kept
// as doubles so that a dual scalar does no work on them.
template <class T>
void transported_frame(const V3<T>& t, const SourceFrame& source, Frame<T>& ref, V3<T>& kh) {
  const Eigen::Vector3d& a = source.tangent;
  const Eigen::Vector3d& v = source.d1;
  const T d = t.x * a[0] + t.y * a[1] + t.z * a[2];
  const V3<T> c(t.z * a[1] - t.y * a[2], t.x * a[2] - t.z * a[0], t.y * a[0] - t.x * a[1]);
  const T inv = 1.0 / (1.0 + d);
  const T k = (c.x * v[0] + c.y * v[1] + c.z * v[2]) * inv;
  ref.d1 = V3<T>(d * v[0] + (c.y * v[2] - c.z * v[1]) + k * c.x,
                 d * v[1] + (c.z * v[0] - c.x * v[2]) + k * c.y,
                 d * v[2] + (c.x * v[1] - c.y * v[0]) + k * c.z);
  ref.d2 = cross(t, ref.d1);
  kh = c * (2.0 * inv);
}

inline double reference_twist(const V3<double> t[2], const Frame<double> ref[2], const V3<double>&,
                              const V3<double>[2], const double[2], double hint) {
  return unwrap_towards(signed_angle(parallel_transport(t[0], t[1], ref[0].d1), ref[1].d1, t[1]),
                        hint);
}

// The reference twist as a Dual1 over (e0, e1, theta0, theta1): its value in
// doubles and its gradient in closed form (see vertex_edge_gradient),
//   dm_ref/de_0 = (I - t0 t0^T)(kb + kh_0) / (2 |e0|),
//   dm_ref/de_1 = (I - t1 t1^T)(kb - kh_1) / (2 |e1|),
// which is all the Jacobian of the gradient needs from it.
template <int N>
Dual1<N> reference_twist(const V3<Dual1<N>> t[2], const Frame<Dual1<N>> ref[2],
                         const V3<Dual1<N>>& kb, const V3<Dual1<N>> kh[2], const Dual1<N> l[2],
                         double hint) {
  static_assert(N >= 6, "the first six seeds are e0 and e1");
  const V3<double> tv[2] = {V3<double>(t[0].values()), V3<double>(t[1].values())};
  const Frame<double> rv[2] = {{V3<double>(ref[0].d1.values()), V3<double>(ref[0].d2.values())},
                               {V3<double>(ref[1].d1.values()), V3<double>(ref[1].d2.values())}};
  Dual1<N> m(reference_twist(tv, rv, V3<double>(), nullptr, nullptr, hint));
  for (int j = 0; j < 2; ++j) {
    const Eigen::Vector3d tj = tv[j].values();
    const Eigen::Vector3d u = kb.values() + (j == 0 ? 1.0 : -1.0) * kh[j].values();
    m.g.template segment<3>(3 * j) = (u - tj * tj.dot(u)) / (2.0 * l[j].v);
  }
  return m;
}

}  // namespace detail

template <class T>
VertexEdgeGradient<T> vertex_edge_gradient(const V3<T>& e0, const V3<T>& e1, const T& theta0,
                                           const T& theta1, const VertexStencil& s) {
  const T l[2] = {norm(e0), norm(e1)};
  const V3<T> t[2] = {e0 / l[0], e1 / l[1]};
  const T chi = 1.0 + dot(t[0], t[1]);
  const V3<T> kb = cross(t[0], t[1]) * (2.0 / chi);
  Frame<T> ref[2];
  V3<T> kh[2];
  for (int j = 0; j < 2; ++j) detail::transported_frame(t[j], s.source[j], ref[j], kh[j]);
  const T theta[2] = {theta0, theta1};
  const T dm =
      theta1 - theta0 + detail::reference_twist(t, ref, kb, kh, l, s.twist_hint) - s.rest_twist;
  const double c = 0.5 / s.voronoi_length;
  const T h = (s.twisting / s.voronoi_length) * dm;

  VertexEdgeGradient<T> out;
  out.bending = T(0.0);
  V3<T> w;
  T rho[2];
  for (int j = 0; j < 2; ++j) {
    const Frame<T> mat = material_frame(ref[j], theta[j]);
    const T k1 = dot(kb, mat.d2), k2 = -dot(kb, mat.d1);
    const T a = k1 - s.rest_kappa[j][0], b = k2 - s.rest_kappa[j][1];
    out.bending += s.bending1 * a * a + s.bending2 * b * b;
    const T f = (c * s.bending1) * a, g = (c * s.bending2) * b;
    w += mat.d2 * f - mat.d1 * g;
    rho[j] = f * k2 - g * k1;
  }
  out.bending = out.bending * (0.5 * c);
  out.twisting = (0.5 * s.twisting / s.voronoi_length) * dm * dm;
  out.theta[0] = rho[0] - h;
  out.theta[1] = rho[1] + h;
  const T kbw = dot(kb, w);
  const V3<T> half_h_kb = kb * (0.5 * h);
  const T inv_chi = 1.0 / chi;
  const V3<T> gt[2] = {(cross(t[1], w) * 2.0 - t[1] * kbw) * inv_chi + half_h_kb,
                       (cross(w, t[0]) * 2.0 - t[0] * kbw) * inv_chi + half_h_kb};
  for (int j = 0; j < 2; ++j) {
    const V3<T> g = gt[j] - kh[j] * (0.5 * out.theta[j]);
    out.e[j] = (g - t[j] * dot(g, t[j])) * (1.0 / l[j]);
  }
  return out;
}

// Plain evaluation of the strains and energies at q.
VertexStrains<double> vertex_strains(const VertexDofs& q, const VertexStencil& s);
VertexEnergy<double> vertex_energy(const VertexDofs& q, const VertexStencil& s);

// Exact gradient and Hessian of E_bend + E_twist with respect to q by
// second-order forward AD of the energy (Dual<11>); returns the energies.
// The reference the fast kernels below are tested against.
VertexEnergy<double> vertex_energy_derivatives(const VertexDofs& q, const VertexStencil& s,
                                               VertexGradient& gradient, VertexHessian& hessian);

// The same gradient from the closed form (vertex_edge_gradient), in plain
// doubles; returns the energies.
VertexEnergy<double> vertex_energy_gradient(const VertexDofs& q, const VertexStencil& s,
                                            VertexGradient& gradient);

// The same gradient and Hessian: the Hessian is the Jacobian of the closed-form
// gradient by first-order forward AD over (e0, e1, theta0, theta1)
// (Dual1<8>), symmetrized; equal to vertex_energy_derivatives to round-off
// at ~1/20 of its cost.
VertexEnergy<double> vertex_energy_hessian(const VertexDofs& q, const VertexStencil& s,
                                           VertexGradient& gradient, VertexHessian& hessian);

}  // namespace xshell
