// Frames of a discrete elastic rod edge (Bergou et al. 2010, "Discrete
// Viscous Threads").
//
// Every edge j stores a source frame (t_hat, d1_hat): its unit tangent and
// first reference director at the last source-frame update. The reference
// frame at the current tangent t is the source frame parallel-transported in
// time, d1_ref = P_{t_hat}^{t} d1_hat, d2_ref = t x d1_ref. The material frame
// is the reference frame rotated about t by the edge's angle theta:
//   d1 =  cos(theta) d1_ref + sin(theta) d2_ref
//   d2 = -sin(theta) d1_ref + cos(theta) d2_ref.
// Updating the source frame to the current reference frame changes nothing
// at the current configuration; it only moves the point the transport starts
// from.
#pragma once

#include <Eigen/Core>

#include "math/rotation.hpp"

namespace xshell {

struct SourceFrame {
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();  // unit
  Eigen::Vector3d d1 = Eigen::Vector3d::UnitY();       // unit, orthogonal to tangent
};

template <class T>
struct Frame {
  V3<T> d1, d2;
};

// Reference frame of an edge whose unit tangent is t.
template <class T>
Frame<T> reference_frame(const V3<T>& t, const SourceFrame& source) {
  Frame<T> f;
  f.d1 = parallel_transport(lift<T>(source.tangent), t, lift<T>(source.d1));
  f.d2 = cross(t, f.d1);
  return f;
}

// Material frame: the reference frame rotated by theta about the tangent.
template <class T>
Frame<T> material_frame(const Frame<T>& ref, const T& theta) {
  using std::cos;
  using std::sin;
  const T c = cos(theta), s = sin(theta);
  return {c * ref.d1 + s * ref.d2, c * ref.d2 - s * ref.d1};
}

}  // namespace xshell
