#include "integrators/deployment/path_predictor.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace xshell::test {

namespace {

// A curved path with a known tangent; its last entry is the parameter
// itself, as the average angle is a linear function of the unknowns.
Eigen::VectorXd path(double a) {
  Eigen::VectorXd q(4);
  q << std::cos(a), std::sin(2 * a), std::exp(a), a;
  return q;
}
Eigen::VectorXd tangent(double a) {
  Eigen::VectorXd t(4);
  t << -std::sin(a), 2 * std::cos(2 * a), std::exp(a), 1.0;
  return t;
}

Eigen::VectorXd second_derivative(double a) {
  Eigen::VectorXd k(4);
  k << -std::cos(a), -4 * std::sin(2 * a), std::exp(a), 0.0;
  return k;
}

// Largest error of the Taylor prediction of path(a + h) from a, and with
// `cubic` the Taylor cubic's through a - h too.
double taylor_error(double a, double h, bool cubic) {
  const PathPoint previous{path(a - h), a - h}, last{path(a), a};
  Eigen::VectorXd predicted = last.q + h * tangent(a);
  if (cubic)
    predicted += taylor_cubic_step(previous, last, tangent(a), second_derivative(a), h,
                                   {true, true, true, true});
  else
    predicted += 0.5 * h * h * second_derivative(a);
  return (predicted - path(a + h)).cwiseAbs().maxCoeff();
}

// Largest error of the Hermite polynomial's prediction of path(a + h) with
// q, t, q'' at a and q, t (and q'' when `quintic`) at a - h.
double hermite_error(double a, double h, bool quintic) {
  const PathPoint previous{path(a - h),
                           a - h,
                           tangent(a - h),
                           {},
                           quintic ? second_derivative(a - h) : Eigen::VectorXd()};
  const PathPoint last{path(a), a};
  const std::vector<bool> all(4, true);
  const Eigen::VectorXd predicted =
      last.q + h * tangent(a) +
      hermite_taylor_step(previous, last, tangent(a), second_derivative(a), h, all, all);
  return (predicted - path(a + h)).cwiseAbs().maxCoeff();
}

// Largest error of the prediction of path(a + h) from a and a - h (with
// the tangent at a - h too when `cubic`).
double error(double a, double h, bool curved, bool cubic = false) {
  const PathPoint previous{path(a - h), a - h, cubic ? tangent(a - h) : Eigen::VectorXd()};
  const PathPoint last{path(a), a};
  Eigen::VectorXd predicted = last.q + h * tangent(a);
  if (curved)
    predicted += path_curvature_step(previous, last, tangent(a), h, {true, true, true, true});
  return (predicted - path(a + h)).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("The quadratic predictor's error falls as h^3, the tangent's as h^2") {
  const double a = 0.7;
  int halvings = 0;
  for (double h = 0.1; h > 0.01; h /= 2) {
    CAPTURE(h);
    const double linear = error(a, h, false) / error(a, h / 2, false);
    const double quadratic = error(a, h, true) / error(a, h / 2, true);
    CHECK(linear == doctest::Approx(4.0).epsilon(0.15));
    CHECK(quadratic == doctest::Approx(8.0).epsilon(0.15));
    CHECK(error(a, h, true) < 0.2 * error(a, h, false));
    ++halvings;
  }
  CHECK(halvings == 4);
}

TEST_CASE("With both tangents the cubic predictor's error falls as h^4") {
  const double a = 0.7;
  int halvings = 0;
  for (double h = 0.1; h > 0.01; h /= 2) {
    CAPTURE(h);
    const double cubic = error(a, h, true, true) / error(a, h / 2, true, true);
    CHECK(cubic == doctest::Approx(16.0).epsilon(0.15));
    // Smaller than the quadratic's once h is small (h^4 against h^3; at
    // h = 0.1 this path's fourth derivative still outweighs its third).
    if (h < 0.03) CHECK(error(a, h, true, true) < 0.5 * error(a, h, true));
    ++halvings;
  }
  CHECK(halvings == 4);
  // Exact on a cubic path (h = 0.3, as large as the fit's own interval).
  const auto cubic_path = [](double s) {
    Eigen::VectorXd q(2);
    q << 1.0 - 2.0 * s + 3.0 * s * s - 0.5 * s * s * s, s;
    return q;
  };
  const auto cubic_tangent = [](double s) {
    Eigen::VectorXd t(2);
    t << -2.0 + 6.0 * s - 1.5 * s * s, 1.0;
    return t;
  };
  const double s = 0.4, h = 0.3;
  const PathPoint previous{cubic_path(s - h), s - h, cubic_tangent(s - h)};
  const PathPoint last{cubic_path(s), s};
  const Eigen::VectorXd predicted =
      last.q + h * cubic_tangent(s) +
      path_curvature_step(previous, last, cubic_tangent(s), h, {true, true});
  CHECK((predicted - cubic_path(s + h)).norm() <= 1e-14);
}

TEST_CASE("The Taylor polynomial's error falls as h^3, the Taylor cubic's as h^4") {
  const double a = 0.7;
  int halvings = 0;
  for (double h = 0.1; h > 0.01; h /= 2) {
    CAPTURE(h);
    const double taylor = taylor_error(a, h, false) / taylor_error(a, h / 2, false);
    const double cubic = taylor_error(a, h, true) / taylor_error(a, h / 2, true);
    CHECK(taylor == doctest::Approx(8.0).epsilon(0.15));
    CHECK(cubic == doctest::Approx(16.0).epsilon(0.15));
    CHECK(taylor_error(a, h, true) < 0.5 * taylor_error(a, h, false));
    ++halvings;
  }
  CHECK(halvings == 4);
  // Exact on a cubic path, on the compared unknowns; the Taylor term alone
  // on the others (and wherever the last step had no length).
  const auto cubic_path = [](double s) {
    return Eigen::Vector3d(1.0 - 2.0 * s + 3.0 * s * s - 0.5 * s * s * s, 2.0 * s * s * s - s * s,
                           s);
  };
  const auto cubic_tangent = [](double s) {
    return Eigen::Vector3d(-2.0 + 6.0 * s - 1.5 * s * s, 6.0 * s * s - 2.0 * s, 1.0);
  };
  const auto cubic_curvature = [](double s) {
    return Eigen::Vector3d(6.0 - 3.0 * s, 12.0 * s - 2.0, 0.0);
  };
  const double s = 0.4, h = 0.3;
  const PathPoint previous{cubic_path(s - 0.2), s - 0.2}, last{cubic_path(s), s};
  const Eigen::VectorXd step = taylor_cubic_step(previous, last, cubic_tangent(s),
                                                 cubic_curvature(s), h, {true, false, true});
  const Eigen::VectorXd predicted = last.q + h * cubic_tangent(s) + step;
  CHECK(std::abs(predicted[0] - cubic_path(s + h)[0]) <= 1e-14);
  CHECK(step[1] == doctest::Approx(0.5 * h * h * cubic_curvature(s)[1]).epsilon(1e-15));
  CHECK(std::abs(step[2]) <= 1e-15);
  const Eigen::VectorXd still =
      taylor_cubic_step(last, last, cubic_tangent(s), cubic_curvature(s), h, {true, true, true});
  CHECK((still - 0.5 * h * h * cubic_curvature(s)).norm() <= 1e-15);
}

TEST_CASE(
    "With the second derivatives the Hermite quartic's error falls as h^5, the quintic's as h^6") {
  const double a = 0.7;
  int halvings = 0;
  for (double h = 0.2; h > 0.03; h /= 2) {
    CAPTURE(h);
    const double quartic = hermite_error(a, h, false) / hermite_error(a, h / 2, false);
    const double quintic = hermite_error(a, h, true) / hermite_error(a, h / 2, true);
    CHECK(quartic == doctest::Approx(32.0).epsilon(0.15));
    CHECK(quintic == doctest::Approx(64.0).epsilon(0.15));
    CHECK(hermite_error(a, h, false) < 0.5 * taylor_error(a, h, true));
    // Higher order pays once h is small against the path's scale (at
    // h = 0.2 this path's sixth derivative still outweighs its fifth).
    if (h < 0.15) CHECK(hermite_error(a, h, true) < 0.5 * hermite_error(a, h, false));
    ++halvings;
  }
  CHECK(halvings == 3);
  // Exact on a quintic path (a longer step than the last one), on the
  // unknowns whose second derivatives compare; the quartic's terms where
  // only values and tangents compare, the Taylor term alone elsewhere.
  const auto coefficients = Eigen::Vector<double, 6>(1.0, -2.0, 3.0, -0.5, 0.8, -1.1);
  const auto quintic = [&](double s, int derivative) {
    double value = 0.0;
    for (int n = derivative; n < 6; ++n) {
      double factor = 1.0;
      for (int m = 0; m < derivative; ++m) factor *= n - m;
      value += coefficients[n] * factor * std::pow(s, n - derivative);
    }
    return value;
  };
  const auto point = [&](double s, int derivative) {
    return Eigen::Vector4d(quintic(s, derivative), quintic(s, derivative), quintic(s, derivative),
                           derivative == 0   ? s
                           : derivative == 1 ? 1.0
                                             : 0.0);
  };
  const double s = 0.4, h0 = 0.2, h = 0.3;
  const PathPoint previous{point(s - h0, 0), s - h0, point(s - h0, 1), {}, point(s - h0, 2)};
  const PathPoint last{point(s, 0), s};
  const Eigen::VectorXd step =
      hermite_taylor_step(previous, last, point(s, 1), point(s, 2), h, {true, true, false, true},
                          {true, false, false, true});
  const Eigen::VectorXd predicted = last.q + h * point(s, 1) + step;
  CHECK(std::abs(predicted[0] - quintic(s + h, 0)) <= 1e-13);
  CHECK(std::abs(predicted[3] - (s + h)) <= 1e-15);  // on a . q = A + h
  // Index 1: the quartic through the same data, off by the quintic's term.
  CHECK(std::abs(predicted[1] - quintic(s + h, 0)) > 1e-3);
  PathPoint without = previous;
  without.curvature.resize(0);
  const Eigen::VectorXd quartic =
      hermite_taylor_step(without, last, point(s, 1), point(s, 2), h, {true, true, false, true},
                          {true, true, false, true});
  CHECK(std::abs(step[1] - quartic[1]) <= 1e-14);
  CHECK(step[2] == doctest::Approx(0.5 * h * h * point(s, 2)[2]).epsilon(1e-15));
}

TEST_CASE("The gradient's second difference along t converges as eps^2 to D3E[t, t]") {
  // E = sum_i x_i^5 / 5 + x_0 x_1^3: g = (x_0^4 + x_1^3, x_1^4 + 3 x_0 x_1^2),
  // D3E[t, t] = (12 x_0^2 t_0^2 + 6 x_1 t_1^2, 12 x_1^2 t_1^2 + 6 x_0 t_1^2 + 12 x_1 t_0 t_1).
  const auto gradient = [](const Eigen::VectorXd& x) {
    return Eigen::Vector2d(std::pow(x[0], 4) + std::pow(x[1], 3),
                           std::pow(x[1], 4) + 3.0 * x[0] * x[1] * x[1]);
  };
  const Eigen::Vector2d x(0.7, -0.4), t(1.3, 0.6);
  const Eigen::Vector2d exact(
      12 * x[0] * x[0] * t[0] * t[0] + 6 * x[1] * t[1] * t[1],
      12 * x[1] * x[1] * t[1] * t[1] + 6 * x[0] * t[1] * t[1] + 12 * x[1] * t[0] * t[1]);
  const auto error = [&](double eps) {
    return (gradient_second_difference(gradient, x, t, eps) - exact).norm();
  };
  int halvings = 0;
  for (double eps = 0.1; eps > 0.01; eps /= 2) {
    CAPTURE(eps);
    CHECK(error(eps) / error(eps / 2) == doctest::Approx(4.0).epsilon(0.1));
    ++halvings;
  }
  CHECK(halvings == 4);
  CHECK(error(1e-3) < 1e-5 * exact.norm());
}

TEST_CASE("The checked second difference is empty where a point is rejected or not finite") {
  // g = (x_0^3, x_0 x_1): D3E[t, t] = (6 x_0 t_0^2, 2 t_0 t_1), exact in the difference.
  Eigen::VectorXd last;  // the point of the last evaluation
  double rejected_above = INFINITY, nan_above = INFINITY;
  const auto gradient = [&](const Eigen::VectorXd& x) {
    last = x;
    if (x[0] > rejected_above) throw std::domain_error("rejected");
    const double g1 = x[0] > nan_above ? NAN : x[0] * x[1];
    return Eigen::Vector2d(x[0] * x[0] * x[0], g1);
  };
  const Eigen::Vector2d x(0.5, 2.0), t(1.0, 3.0);
  const Eigen::VectorXd third = gradient_second_difference_or_empty(gradient, x, t, 1e-3);
  REQUIRE(third.size() == 2);
  CHECK(third[0] == doctest::Approx(6.0 * 0.5).epsilon(1e-6));
  CHECK(third[1] == doctest::Approx(6.0).epsilon(1e-6));
  CHECK(last == x);
  rejected_above = 0.5001;  // x + eps t is rejected
  CHECK(gradient_second_difference_or_empty(gradient, x, t, 1e-3).size() == 0);
  CHECK(last == x);  // evaluated at x once more
  rejected_above = INFINITY;
  nan_above = 0.5001;
  CHECK(gradient_second_difference_or_empty(gradient, x, t, 1e-3).size() == 0);
}

TEST_CASE("The curvature step leaves the parameter and the unknowns not compared unchanged") {
  const double a = 0.3, h = 0.05;
  const PathPoint previous{path(a - 0.1), a - 0.1}, last{path(a), a};
  const Eigen::VectorXd step =
      path_curvature_step(previous, last, tangent(a), h, {true, false, true, true});
  CHECK(step[0] != 0.0);
  CHECK(step[1] == 0.0);
  CHECK(std::abs(step[3]) <= 1e-15);  // the prediction stays on a . q = A + h
  // A longer step than the last one: the same curvature, scaled by h^2.
  const Eigen::VectorXd twice =
      path_curvature_step(previous, last, tangent(a), 2 * h, {true, false, true, true});
  CHECK((twice - 4.0 * step).norm() <= 1e-14 * twice.norm());
  const PathPoint same{path(a), a};
  CHECK(path_curvature_step(same, last, tangent(a), h, {true, true, true, true}).norm() == 0.0);
}

}  // namespace xshell::test
