// A minimal 3-vector over any scalar (double or Dual<N>), for the kernels
// that are written once and differentiated automatically. Eigen is used for
// everything that is plain double.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "dual.hpp"

namespace xshell {

template <class T>
struct V3 {
  T x, y, z;

  V3() : x(0.0), y(0.0), z(0.0) {}
  V3(T a, T b, T c) : x(std::move(a)), y(std::move(b)), z(std::move(c)) {}
  explicit V3(const Eigen::Vector3d& v) : x(v[0]), y(v[1]), z(v[2]) {}

  V3& operator+=(const V3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  V3& operator-=(const V3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  friend V3 operator+(V3 a, const V3& b) { return a += b; }
  friend V3 operator-(V3 a, const V3& b) { return a -= b; }
  friend V3 operator-(const V3& a) { return V3(-a.x, -a.y, -a.z); }
  template <class S>
  friend V3 operator*(const V3& a, const S& s) {
    return V3(a.x * s, a.y * s, a.z * s);
  }
  template <class S>
  friend V3 operator*(const S& s, const V3& a) {
    return V3(a.x * s, a.y * s, a.z * s);
  }
  template <class S>
  friend V3 operator/(const V3& a, const S& s) {
    return V3(a.x / s, a.y / s, a.z / s);
  }

  Eigen::Vector3d values() const { return {value(x), value(y), value(z)}; }
};

template <class T>
T dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return V3<T>(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

template <class T>
T norm(const V3<T>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}

// Converts a constant Eigen vector into any scalar type.
template <class T>
V3<T> lift(const Eigen::Vector3d& v) {
  return V3<T>(T(v[0]), T(v[1]), T(v[2]));
}

}  // namespace xshell
