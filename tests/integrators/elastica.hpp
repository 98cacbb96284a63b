// The planar elastica of a cantilever under a dead tip load perpendicular to
// its clamped direction, by shooting: with s in [0, 1] and
// alpha = P L^2 / (E I), theta'' = -alpha cos(theta), theta(0) = 0,
// theta'(1) = 0. Returns the tip deflection along the load and the
// shortening, both over L (Bisshopp & Drucker 1945).
#pragma once

#include <cmath>

namespace xshell::test {

struct ElasticaTip {
  double deflection = 0.0;  // v / L
  double shortening = 0.0;  // u / L
};

inline ElasticaTip cantilever_elastica(double alpha) {
  const int steps = 4000;
  const double h = 1.0 / steps;
  // Integrates from theta'(0) = k0; returns theta'(1) and the tip.
  auto shoot = [&](double k0, ElasticaTip* tip) {
    double th = 0.0, k = k0, x = 0.0, y = 0.0;
    auto f = [&](double t, double kk, double& dt, double& dk) {
      dt = kk;
      dk = -alpha * std::cos(t);
      (void)kk;
    };
    for (int i = 0; i < steps; ++i) {
      double a1, b1, a2, b2, a3, b3, a4, b4;
      f(th, k, a1, b1);
      f(th + 0.5 * h * a1, k + 0.5 * h * b1, a2, b2);
      f(th + 0.5 * h * a2, k + 0.5 * h * b2, a3, b3);
      f(th + h * a3, k + h * b3, a4, b4);
      // Position by Simpson's rule on the same stages.
      const double tm = th + 0.5 * h * a1, te = th + h * a4;
      (void)tm;
      x += h / 6.0 * (std::cos(th) + 4.0 * std::cos(th + 0.5 * h * (a1 + a2) / 2.0) + std::cos(te));
      y += h / 6.0 * (std::sin(th) + 4.0 * std::sin(th + 0.5 * h * (a1 + a2) / 2.0) + std::sin(te));
      th += h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4);
      k += h / 6.0 * (b1 + 2 * b2 + 2 * b3 + b4);
    }
    if (tip) *tip = {y, 1.0 - x};
    return k;
  };
  // theta'(0) lies in (0, alpha]; theta'(1) is increasing in it.
  double lo = 0.0, hi = alpha;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid, nullptr) > 0.0 ? hi : lo) = mid;
  }
  ElasticaTip tip;
  shoot(0.5 * (lo + hi), &tip);
  return tip;
}

}  // namespace xshell::test
