// Rotations by a rotation vector ("angle-scaled axis") w, and parallel
// transport between unit vectors, over any scalar (double or Dual<N>).
//
// R(w) v = v + a(|w|^2) w x v + b(|w|^2) w x (w x v) (Rodrigues), with
//   a = sin|w| / |w|,  b = (1 - cos|w|) / |w|^2 = 2 sin^2(|w|/2) / |w|^2.
// Both are smooth functions of |w|^2; near w = 0, exactly where every joint's
// rotation vector sits after a fold, they are evaluated by their Taylor
// series in |w|^2, so the value and the first and second derivatives with
// respect to w are exact to round-off there (no sqrt of 0 is ever taken).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "vec3.hpp"

namespace xshell {

namespace detail {
// Below this |w|^2 the series is used; its first neglected term is
// |w|^8 / 9! < 1e-30 relative, far below round-off, also after two
// derivatives.
constexpr double kRotationSeriesThreshold = 1e-6;
}  // namespace detail

// Coefficients a and b above as functions of s = |w|^2.
template <class T>
void rodrigues_coefficients(const T& s, T& a, T& b) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (value(s) < detail::kRotationSeriesThreshold) {
    a = 1.0 - s * (1.0 / 6.0 - s * (1.0 / 120.0 - s * (1.0 / 5040.0)));
    b = 0.5 - s * (1.0 / 24.0 - s * (1.0 / 720.0 - s * (1.0 / 40320.0)));
  } else {
    const T theta = sqrt(s);
    const T half_sin = sin(0.5 * theta);
    a = sin(theta) / theta;
    b = 2.0 * half_sin * half_sin / s;
  }
}

// R(w) v.
template <class T>
V3<T> rotate(const V3<T>& w, const V3<T>& v) {
  T a, b;
  rodrigues_coefficients(dot(w, w), a, b);
  const V3<T> wv = cross(w, v);
  return v + a * wv + b * cross(w, wv);
}

// The rotation matrix R(w).
inline Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix3d r;
  for (int k = 0; k < 3; ++k) {
    r.col(k) =
        rotate(V3<double>(w), V3<double>(Eigen::Vector3d(Eigen::Vector3d::Unit(k)))).values();
  }
  return r;
}

// Parallel transport P_a^b v: the rotation about a x b taking the unit vector
// a to the unit vector b, applied to v. Undefined for b = -a.
//   P_a^b v = (a.b) v + (a x b) x v + ((a x b).v / (1 + a.b)) (a x b)
template <class T>
V3<T> parallel_transport(const V3<T>& a, const V3<T>& b, const V3<T>& v) {
  const V3<T> c = cross(a, b);
  const T d = dot(a, b);
  return d * v + cross(c, v) + (dot(c, v) / (1.0 + d)) * c;
}

// Signed angle from u to v about the unit axis n (u, v orthogonal to n).
template <class T>
T signed_angle(const V3<T>& u, const V3<T>& v, const V3<T>& n) {
  using std::atan2;
  return atan2(dot(cross(u, v), n), dot(u, v));
}

// Left Jacobian of the exponential map: for R(w(t)), the spatial angular
// velocity is J_l(w) w'. J_l = I + b [w]x + c [w]x^2 with b as above and
// c = (|w| - sin|w|) / |w|^3 (series near 0).
inline Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& w) {
  const double s = w.squaredNorm();
  double a, b, c;
  rodrigues_coefficients(s, a, b);
  if (s < detail::kRotationSeriesThreshold) {
    c = 1.0 / 6.0 - s * (1.0 / 120.0 - s / 5040.0);
  } else {
    const double theta = std::sqrt(s);
    c = (theta - std::sin(theta)) / (s * theta);
  }
  Eigen::Matrix3d k;
  k << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return Eigen::Matrix3d::Identity() + b * k + c * k * k;
}

// Any unit vector orthogonal to the unit vector t.
inline Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& t) {
  Eigen::Vector3d trial =
      std::abs(t.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (trial - trial.dot(t) * t).normalized();
}

}  // namespace xshell
