// Small helpers for the toy objectives of the integrator tests, written with
// the model's second-order automatic differentiation (math/dual.hpp): a toy
// energy term is a formula in Dual<N>, and its exact local gradient and
// Hessian follow.
#pragma once

#include <array>

#include "math/dual.hpp"

namespace xshell::test {

template <int N>
Dual<N> square(const Dual<N>& a) {
  return a * a;
}

// 3-vectors of duals, for node positions.
template <int N>
using Dual3 = std::array<Dual<N>, 3>;

template <int N>
Dual<N> dot(const Dual3<N>& a, const Dual3<N>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

template <int N>
Dual3<N> difference(const Dual3<N>& a, const Dual3<N>& b) {
  Dual3<N> r;
  for (int i = 0; i < 3; ++i) r[i] = a[i] - b[i];
  return r;
}

}  // namespace xshell::test
