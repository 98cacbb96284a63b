// Second-order forward-mode automatic differentiation over a fixed, small
// number of variables.
//
// A Dual<N> carries a value, its gradient (N) and its Hessian (N x N) with
// respect to N seed variables; arithmetic propagates all three exactly (to
// round-off), by the chain rule
//   f(u)'' = f'(u) u'' + f''(u) u' u'^T.
// The rod's energy kernels are written once as templates over their scalar
// and evaluated with Dual<N> on their local stencil (N = 11 for a bending or
// twisting stencil, 9 for a joint): this gives the exact derivatives of the
// finite-transport formulation everywhere, not only right after a
// source-frame update, at a cost proportional to N^2 per operation.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace xshell {

template <int N>
struct Dual {
  using Gradient = Eigen::Matrix<double, N, 1>;
  using Hessian = Eigen::Matrix<double, N, N>;

  double v = 0.0;
  Gradient g = Gradient::Zero();
  Hessian h = Hessian::Zero();

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants mix freely with duals

 private:
  // Results that every operation overwrites entirely skip the zero fill.
  struct Uninitialized {};
  explicit Dual(Uninitialized) : g(), h() {}

 public:
  // The i-th seed variable with the given value.
  static Dual variable(int i, double value) {
    Dual d(value);
    d.g[i] = 1.0;
    return d;
  }

  Dual& operator+=(const Dual& o) {
    v += o.v;
    g += o.g;
    h += o.h;
    return *this;
  }
  Dual& operator-=(const Dual& o) {
    v -= o.v;
    g -= o.g;
    h -= o.h;
    return *this;
  }
  Dual& operator*=(const Dual& o) {
    *this = *this * o;
    return *this;
  }
  Dual& operator/=(const Dual& o) {
    *this = *this / o;
    return *this;
  }

  friend Dual operator-(const Dual& a) {
    Dual r;
    r.v = -a.v;
    r.g = -a.g;
    r.h = -a.h;
    return r;
  }
  friend Dual operator+(Dual a, const Dual& b) { return a += b; }
  friend Dual operator-(Dual a, const Dual& b) { return a -= b; }
  friend Dual operator*(const Dual& a, const Dual& b) {
    Dual r(Uninitialized{});
    r.v = a.v * b.v;
    r.g = a.v * b.g + b.v * a.g;
    // One pass over the Hessian (rather than four), column by column.
    for (int j = 0; j < N; ++j)
      r.h.col(j) = a.v * b.h.col(j) + b.v * a.h.col(j) + b.g[j] * a.g + a.g[j] * b.g;
    return r;
  }
  friend Dual operator/(const Dual& a, const Dual& b) { return a * reciprocal(b); }

  friend Dual operator+(Dual a, double b) {
    a.v += b;
    return a;
  }
  friend Dual operator+(double b, Dual a) {
    a.v += b;
    return a;
  }
  friend Dual operator-(Dual a, double b) {
    a.v -= b;
    return a;
  }
  friend Dual operator-(double b, const Dual& a) {
    Dual r = -a;
    r.v += b;
    return r;
  }
  friend Dual operator*(Dual a, double b) {
    a.v *= b;
    a.g *= b;
    a.h *= b;
    return a;
  }
  friend Dual operator*(double b, Dual a) { return a * b; }
  friend Dual operator/(Dual a, double b) { return a * (1.0 / b); }
  friend Dual operator/(double b, const Dual& a) { return b * reciprocal(a); }

  friend bool operator<(const Dual& a, const Dual& b) { return a.v < b.v; }
  friend bool operator>(const Dual& a, const Dual& b) { return a.v > b.v; }

  // Applies a scalar function given its value and first two derivatives at v.
  friend Dual chain(const Dual& a, double f, double df, double d2f) {
    Dual r(Uninitialized{});
    r.v = f;
    r.g = df * a.g;
    for (int j = 0; j < N; ++j) r.h.col(j) = df * a.h.col(j) + (d2f * a.g[j]) * a.g;
    return r;
  }
  friend Dual reciprocal(const Dual& a) {
    const double inv = 1.0 / a.v;
    return chain(a, inv, -inv * inv, 2.0 * inv * inv * inv);
  }
  friend Dual sqrt(const Dual& a) {
    const double s = std::sqrt(a.v);
    return chain(a, s, 0.5 / s, -0.25 / (s * a.v));
  }
  friend Dual sin(const Dual& a) {
    const double s = std::sin(a.v), c = std::cos(a.v);
    return chain(a, s, c, -s);
  }
  friend Dual cos(const Dual& a) {
    const double s = std::sin(a.v), c = std::cos(a.v);
    return chain(a, c, -s, -c);
  }
  // atan2(y, x) with its exact first and second derivatives in (y, x).
  friend Dual atan2(const Dual& y, const Dual& x) {
    const double r2 = x.v * x.v + y.v * y.v;
    Dual r;
    r.v = std::atan2(y.v, x.v);
    // d/dy = x/r2, d/dx = -y/r2.
    const double fy = x.v / r2, fx = -y.v / r2;
    // Second derivatives: f_yy = -2xy/r4, f_xx = 2xy/r4, f_xy = (y^2-x^2)/r4.
    const double r4 = r2 * r2;
    const double fyy = -2.0 * x.v * y.v / r4, fxx = -fyy, fxy = (y.v * y.v - x.v * x.v) / r4;
    r.g = fy * y.g + fx * x.g;
    r.h = fy * y.h + fx * x.h;
    r.h.noalias() += fyy * (y.g * y.g.transpose()) + fxx * (x.g * x.g.transpose());
    r.h.noalias() += fxy * (y.g * x.g.transpose() + x.g * y.g.transpose());
    return r;
  }
};

// Value of a plain or dual scalar.
inline double value(double x) { return x; }
template <int N>
double value(const Dual<N>& x) {
  return x.v;
}

}  // namespace xshell
