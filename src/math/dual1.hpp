// First-order forward-mode automatic differentiation over a fixed, small
// number of variables: a Dual1<N> carries a value and its gradient (N).
//
// Costs O(N) per operation (Dual<N> in dual.hpp costs O(N^2)). Used where
// only first derivatives are wanted: the Jacobian of a closed-form gradient
// (which is the Hessian; vertex_stencil.hpp) and the Jacobian of a joint's
// terminal edge for gradients. Same interface as Dual<N> (value(), chain,
// sqrt, sin, cos, atan2), so the templated kernels accept either.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "dual.hpp"
#include "inlining.hpp"

namespace xshell {

template <int N>
struct Dual1 {
  using Gradient = Eigen::Matrix<double, N, 1>;

  double v = 0.0;
  Gradient g = Gradient::Zero();

  Dual1() = default;
  Dual1(double value) : v(value) {}  // NOLINT: constants mix freely with duals

  // The i-th seed variable with the given value.
  static Dual1 variable(int i, double value) {
    Dual1 d(value);
    d.g[i] = 1.0;
    return d;
  }

  XSHELL_DUAL_INLINE Dual1& operator+=(const Dual1& o) {
    v += o.v;
    g += o.g;
    return *this;
  }
  XSHELL_DUAL_INLINE Dual1& operator-=(const Dual1& o) {
    v -= o.v;
    g -= o.g;
    return *this;
  }
  XSHELL_DUAL_INLINE Dual1& operator*=(const Dual1& o) {
    *this = *this * o;
    return *this;
  }
  XSHELL_DUAL_INLINE Dual1& operator/=(const Dual1& o) {
    *this = *this / o;
    return *this;
  }

  XSHELL_DUAL_INLINE friend Dual1 operator-(const Dual1& a) {
    Dual1 r;
    r.v = -a.v;
    r.g = -a.g;
    return r;
  }
  XSHELL_DUAL_INLINE friend Dual1 operator+(Dual1 a, const Dual1& b) { return a += b; }
  XSHELL_DUAL_INLINE friend Dual1 operator-(Dual1 a, const Dual1& b) { return a -= b; }
  XSHELL_DUAL_INLINE friend Dual1 operator*(const Dual1& a, const Dual1& b) {
    Dual1 r;
    r.v = a.v * b.v;
    r.g = a.v * b.g + b.v * a.g;
    return r;
  }
  XSHELL_DUAL_INLINE friend Dual1 operator/(const Dual1& a, const Dual1& b) {
    const double inv = 1.0 / b.v;
    Dual1 r;
    r.v = a.v * inv;
    r.g = (a.g - r.v * b.g) * inv;
    return r;
  }

  XSHELL_DUAL_INLINE friend Dual1 operator+(Dual1 a, double b) {
    a.v += b;
    return a;
  }
  XSHELL_DUAL_INLINE friend Dual1 operator+(double b, Dual1 a) {
    a.v += b;
    return a;
  }
  XSHELL_DUAL_INLINE friend Dual1 operator-(Dual1 a, double b) {
    a.v -= b;
    return a;
  }
  XSHELL_DUAL_INLINE friend Dual1 operator-(double b, const Dual1& a) {
    Dual1 r = -a;
    r.v += b;
    return r;
  }
  XSHELL_DUAL_INLINE friend Dual1 operator*(Dual1 a, double b) {
    a.v *= b;
    a.g *= b;
    return a;
  }
  XSHELL_DUAL_INLINE friend Dual1 operator*(double b, Dual1 a) { return a * b; }
  XSHELL_DUAL_INLINE friend Dual1 operator/(Dual1 a, double b) { return a * (1.0 / b); }
  XSHELL_DUAL_INLINE friend Dual1 operator/(double b, const Dual1& a) {
    const double inv = 1.0 / a.v;
    Dual1 r;
    r.v = b * inv;
    r.g = (-r.v * inv) * a.g;
    return r;
  }

  friend bool operator<(const Dual1& a, const Dual1& b) { return a.v < b.v; }
  friend bool operator>(const Dual1& a, const Dual1& b) { return a.v > b.v; }

  // Applies a scalar function given its value and derivative at v.
  XSHELL_DUAL_INLINE friend Dual1 chain(const Dual1& a, double f, double df) {
    Dual1 r;
    r.v = f;
    r.g = df * a.g;
    return r;
  }
  XSHELL_DUAL_INLINE friend Dual1 sqrt(const Dual1& a) {
    const double s = std::sqrt(a.v);
    return chain(a, s, 0.5 / s);
  }
  XSHELL_DUAL_INLINE friend Dual1 sin(const Dual1& a) {
    return chain(a, std::sin(a.v), std::cos(a.v));
  }
  XSHELL_DUAL_INLINE friend Dual1 cos(const Dual1& a) {
    return chain(a, std::cos(a.v), -std::sin(a.v));
  }
  // atan2(y, x): d/dy = x/r2, d/dx = -y/r2.
  XSHELL_DUAL_INLINE friend Dual1 atan2(const Dual1& y, const Dual1& x) {
    const double r2 = x.v * x.v + y.v * y.v;
    Dual1 r;
    r.v = std::atan2(y.v, x.v);
    r.g = (x.v / r2) * y.g - (y.v / r2) * x.g;
    return r;
  }
};

template <int N>
double value(const Dual1<N>& x) {
  return x.v;
}

}  // namespace xshell
