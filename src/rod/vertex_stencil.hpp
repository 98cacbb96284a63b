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

namespace xshell {

struct VertexStencil {
  SourceFrame source[2];          // source frames of edges i-1 and i
  double rest_kappa[2][2] = {};   // [edge j][kappa1, kappa2] at rest
  double rest_twist = 0.0;        // m_rest
  double twist_hint = 0.0;        // reference twist at the last update
  double voronoi_length = 1.0;    // V
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

// Plain evaluation of the strains and energies at q.
VertexStrains<double> vertex_strains(const VertexDofs& q, const VertexStencil& s);
VertexEnergy<double> vertex_energy(const VertexDofs& q, const VertexStencil& s);

// Exact gradient and Hessian of E_bend + E_twist with respect to q; returns
// the energies.
VertexEnergy<double> vertex_energy_derivatives(const VertexDofs& q, const VertexStencil& s,
                                               VertexGradient& gradient, VertexHessian& hessian);

}  // namespace xshell
