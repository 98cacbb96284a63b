// Second-order forward-mode automatic differentiation for the toy
// objectives of the integrator tests: a Jet<N> carries a value, its gradient
// and its Hessian with respect to N local variables, so a toy energy term
// is written once, as a formula, and its exact derivatives follow.
//
// Rules: (a b)'' = a b'' + b a'' + a' b'^T + b' a'^T and, for a scalar
// function f, f(a)'' = f'(a) a'' + f''(a) a' a'^T.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace xshell::test {

template <int N>
struct Jet {
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;

  double v = 0.0;
  Vector g = Vector::Zero();
  Matrix h = Matrix::Zero();

  Jet() = default;
  Jet(double value) : v(value) {}  // NOLINT: constants convert implicitly

  static Jet variable(double value, int index) {
    Jet x(value);
    x.g[index] = 1.0;
    return x;
  }
};

// f(a) from f(a.v), f'(a.v), f''(a.v).
template <int N>
Jet<N> chain(const Jet<N>& a, double f, double df, double d2f) {
  Jet<N> r;
  r.v = f;
  r.g = df * a.g;
  r.h = df * a.h + d2f * a.g * a.g.transpose();
  return r;
}

template <int N>
Jet<N> operator+(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> r;
  r.v = a.v + b.v;
  r.g = a.g + b.g;
  r.h = a.h + b.h;
  return r;
}

template <int N>
Jet<N> operator-(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> r;
  r.v = a.v - b.v;
  r.g = a.g - b.g;
  r.h = a.h - b.h;
  return r;
}

template <int N>
Jet<N> operator-(const Jet<N>& a) {
  return chain(a, -a.v, -1.0, 0.0);
}

template <int N>
Jet<N> operator*(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> r;
  r.v = a.v * b.v;
  r.g = a.v * b.g + b.v * a.g;
  r.h = a.v * b.h + b.v * a.h + a.g * b.g.transpose() + b.g * a.g.transpose();
  return r;
}

template <int N>
Jet<N> inverse(const Jet<N>& a) {
  const double i = 1.0 / a.v;
  return chain(a, i, -i * i, 2.0 * i * i * i);
}

template <int N>
Jet<N> operator/(const Jet<N>& a, const Jet<N>& b) {
  return a * inverse(b);
}

template <int N>
Jet<N> operator+(const Jet<N>& a, double b) {
  return chain(a, a.v + b, 1.0, 0.0);
}
template <int N>
Jet<N> operator+(double b, const Jet<N>& a) {
  return a + b;
}
template <int N>
Jet<N> operator-(const Jet<N>& a, double b) {
  return a + (-b);
}
template <int N>
Jet<N> operator-(double b, const Jet<N>& a) {
  return chain(a, b - a.v, -1.0, 0.0);
}
template <int N>
Jet<N> operator*(const Jet<N>& a, double b) {
  return chain(a, a.v * b, b, 0.0);
}
template <int N>
Jet<N> operator*(double b, const Jet<N>& a) {
  return a * b;
}
template <int N>
Jet<N> operator/(const Jet<N>& a, double b) {
  return a * (1.0 / b);
}

template <int N>
Jet<N> sqrt(const Jet<N>& a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s, -0.25 / (s * a.v));
}

template <int N>
Jet<N> square(const Jet<N>& a) {
  return chain(a, a.v * a.v, 2.0 * a.v, 2.0);
}

template <int N>
Jet<N> cos(const Jet<N>& a) {
  return chain(a, std::cos(a.v), -std::sin(a.v), -std::cos(a.v));
}

// 3-vectors of jets, for node positions.
template <int N>
using Jet3 = std::array<Jet<N>, 3>;

template <int N>
Jet<N> dot(const Jet3<N>& a, const Jet3<N>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

template <int N>
Jet3<N> difference(const Jet3<N>& a, const Jet3<N>& b) {
  Jet3<N> r;
  for (int i = 0; i < 3; ++i) r[i] = a[i] - b[i];
  return r;
}

}  // namespace xshell::test
