// Reference solutions of the inextensible planar elastica, for rods clamped
// at one end (Bisshopp & Drucker 1945; Mattiasson 1981 tabulates them).
//
// Cantilever of length L under a dead tip load P perpendicular to its
// clamped direction, alpha = P L^2 / (E I), theta the tangent's angle from
// the clamped direction (theta(0) = 0, theta(L) = theta_L at the tip):
//   E I theta'' = -P cos(theta), theta'(L) = 0.
// Twice integrated, with the modulus p = sqrt((1 + sin theta_L) / 2) and
// phi_0 = asin(1 / (p sqrt 2)) (substitution 1 + sin theta = 2 p^2 sin^2 phi):
//   sqrt(alpha) = K(p) - F(phi_0, p),
//   v / L = 1 - 2 / sqrt(alpha) (E(p) - E(phi_0, p))   (tip deflection along P),
//   u / L = 1 - sqrt(2 sin(theta_L) / alpha)           (tip shortening),
// F, E the incomplete elliptic integrals of the first and second kind, K, E
// the complete ones (modulus, not parameter: std::ellint_1(p, phi)).
// cantilever_elastica_by_shooting integrates the differential equation
// instead, as an independent check of the closed form.
//
// Clamped-free column of length L under an axial dead load P above
// P_cr = pi^2 E I / (4 L^2): half of a pinned-pinned elastica of length 2 L.
// With k = sin(theta_tip / 2), theta_tip the tip's angle from the axis,
//   P / P_cr = (2 K(k) / pi)^2,   tip lateral deflection delta / L = 2 k / K(k)
// (the pinned-pinned column of length l has midspan deflection k l / K(k)).
#pragma once

#include <cmath>

namespace xshell::test {

struct ElasticaTip {
  double deflection = 0.0;  // v / L, along the load
  double shortening = 0.0;  // u / L, along the clamped direction
  double tip_angle = 0.0;   // theta_L, radians
};

// The cantilever by the closed form above; theta_L by bisection (sqrt(alpha)
// increases with theta_L from 0 to infinity on (0, pi / 2)).
inline ElasticaTip cantilever_elastica(double alpha) {
  auto modulus = [](double theta_l) { return std::sqrt(0.5 * (1.0 + std::sin(theta_l))); };
  auto phi_0 = [](double p) { return std::asin(1.0 / (p * std::sqrt(2.0))); };
  double lo = 0.0, hi = 0.5 * M_PI;
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double p = modulus(mid);
    (std::comp_ellint_1(p) - std::ellint_1(p, phi_0(p)) < std::sqrt(alpha) ? lo : hi) = mid;
  }
  const double theta_l = 0.5 * (lo + hi), p = modulus(theta_l);
  ElasticaTip tip;
  tip.tip_angle = theta_l;
  tip.deflection =
      1.0 - 2.0 / std::sqrt(alpha) * (std::comp_ellint_2(p) - std::ellint_2(p, phi_0(p)));
  tip.shortening = 1.0 - std::sqrt(2.0 * std::sin(theta_l) / alpha);
  return tip;
}

// The cantilever by shooting: theta'' = -alpha cos(theta) on s in [0, 1],
// theta(0) = 0, from theta'(0) = k0, classical Runge-Kutta on
// (theta, theta', x, y) with `steps` steps; k0 by bisection on theta'(1) = 0
// (theta'(1) increases with k0, which lies in (0, alpha]). Fourth order.
inline ElasticaTip cantilever_elastica_by_shooting(double alpha, int steps = 2000) {
  const double h = 1.0 / steps;
  struct State {
    double theta, kappa, x, y;
  };
  auto rate = [&](const State& s) {
    return State{s.kappa, -alpha * std::cos(s.theta), std::cos(s.theta), std::sin(s.theta)};
  };
  auto plus = [](const State& a, double c, const State& b) {
    return State{a.theta + c * b.theta, a.kappa + c * b.kappa, a.x + c * b.x, a.y + c * b.y};
  };
  auto shoot = [&](double k0) {
    State s{0.0, k0, 0.0, 0.0};
    for (int i = 0; i < steps; ++i) {
      const State a = rate(s), b = rate(plus(s, 0.5 * h, a)), c = rate(plus(s, 0.5 * h, b)),
                  d = rate(plus(s, h, c));
      s = plus(s, h / 6.0,
               State{a.theta + 2 * b.theta + 2 * c.theta + d.theta,
                     a.kappa + 2 * b.kappa + 2 * c.kappa + d.kappa, a.x + 2 * b.x + 2 * c.x + d.x,
                     a.y + 2 * b.y + 2 * c.y + d.y});
    }
    return s;
  };
  double lo = 0.0, hi = alpha;
  for (int i = 0; i < 200 && hi - lo > 1e-16 * alpha; ++i) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid).kappa > 0.0 ? hi : lo) = mid;
  }
  const State end = shoot(0.5 * (lo + hi));
  return {end.y, 1.0 - end.x, end.theta};
}

// Tip lateral deflection over L of the clamped-free column at
// load_ratio = P / P_cr > 1; k by bisection ((2 K(k) / pi)^2 increases from
// 1 to infinity on (0, 1)).
inline double postbuckled_tip_deflection(double load_ratio) {
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::pow(2.0 * std::comp_ellint_1(mid) / M_PI, 2) < load_ratio ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi);
  return 2.0 * k / std::comp_ellint_1(k);
}

}  // namespace xshell::test
