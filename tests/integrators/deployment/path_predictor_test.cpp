#include "integrators/deployment/path_predictor.hpp"

#include <doctest/doctest.h>

#include <cmath>
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
