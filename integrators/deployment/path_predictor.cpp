#include "integrators/deployment/path_predictor.hpp"

#include <cmath>
#include <stdexcept>

namespace xshell {

Eigen::VectorXd path_curvature_step(const PathPoint& previous, const PathPoint& last,
                                    const Eigen::VectorXd& tangent, double h,
                                    const std::vector<bool>& comparable) {
  Eigen::VectorXd step = Eigen::VectorXd::Zero(last.q.size());
  const double h0 = last.value - previous.value;
  if (!(std::abs(h0) > 0.0)) return step;
  const double r = h / h0;
  const bool cubic = previous.tangent.size() == last.q.size();
  for (Eigen::Index i = 0; i < step.size(); ++i) {
    if (!comparable[i]) continue;
    const double d = previous.q[i] - last.q[i] + h0 * tangent[i];
    if (!cubic) {
      step[i] = r * r * d;
      continue;
    }
    const double e = h0 * (previous.tangent[i] - tangent[i]);
    step[i] = r * r * (3.0 * d + e) + r * r * r * (2.0 * d + e);
  }
  return step;
}

Eigen::VectorXd taylor_cubic_step(const PathPoint& previous, const PathPoint& last,
                                  const Eigen::VectorXd& tangent, const Eigen::VectorXd& curvature,
                                  double h, const std::vector<bool>& comparable) {
  Eigen::VectorXd step = 0.5 * h * h * curvature;
  const double h0 = last.value - previous.value;
  if (!(std::abs(h0) > 0.0)) return step;
  const double r3 = (h / h0) * (h / h0) * (h / h0);
  for (Eigen::Index i = 0; i < step.size(); ++i) {
    if (!comparable[i]) continue;
    const double d = previous.q[i] - last.q[i] + h0 * tangent[i];
    step[i] += r3 * (0.5 * h0 * h0 * curvature[i] - d);
  }
  return step;
}

Eigen::VectorXd hermite_taylor_step(const PathPoint& previous, const PathPoint& last,
                                    const Eigen::VectorXd& tangent,
                                    const Eigen::VectorXd& curvature, double h,
                                    const std::vector<bool>& comparable,
                                    const std::vector<bool>& curvature_comparable) {
  Eigen::VectorXd step = 0.5 * h * h * curvature;
  const double h0 = last.value - previous.value;
  if (!(std::abs(h0) > 0.0) || previous.tangent.size() != last.q.size()) return step;
  const bool quintic = previous.curvature.size() == last.q.size();
  const double r = h / h0;
  const double r3 = r * r * r, r4 = r3 * r, r5 = r4 * r;
  const double h02 = h0 * h0;
  for (Eigen::Index i = 0; i < step.size(); ++i) {
    if (!comparable[i]) continue;
    // With u = (A - A1) / h0: q1 + u T1 + u^2/2 K1 + a u^3 + b u^4 (+ c u^5)
    // matches q0, T0 (and K0) at u = -1 (T = h0 t, K = h0^2 k).
    const double r0 = previous.q[i] - last.q[i] + h0 * tangent[i] - 0.5 * h02 * curvature[i];
    const double r1 = h0 * (previous.tangent[i] - tangent[i]) + h02 * curvature[i];
    if (quintic && curvature_comparable[i]) {
      const double r2 = h02 * (previous.curvature[i] - curvature[i]);
      step[i] += r3 * (-10.0 * r0 - 4.0 * r1 - 0.5 * r2) + r4 * (-15.0 * r0 - 7.0 * r1 - r2) +
                 r5 * (-6.0 * r0 - 3.0 * r1 - 0.5 * r2);
    } else {
      step[i] += r3 * (-4.0 * r0 - r1) + r4 * (-3.0 * r0 - r1);
    }
  }
  return step;
}

Eigen::VectorXd gradient_second_difference(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& gradient,
    const Eigen::VectorXd& q, const Eigen::VectorXd& t, double eps) {
  const Eigen::VectorXd plus = gradient(q + eps * t);
  const Eigen::VectorXd minus = gradient(q - eps * t);
  return (plus - 2.0 * gradient(q) + minus) / (eps * eps);
}

Eigen::VectorXd gradient_second_difference_or_empty(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& gradient,
    const Eigen::VectorXd& q, const Eigen::VectorXd& t, double eps) {
  Eigen::VectorXd third;
  try {
    third = gradient_second_difference(gradient, q, t, eps);
  } catch (const std::domain_error&) {
    gradient(q);
    return {};
  }
  return third.allFinite() ? third : Eigen::VectorXd();
}

}  // namespace xshell
