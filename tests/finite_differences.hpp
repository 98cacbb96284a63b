// Finite-difference checks shared by the test programs. Central differences
// of step h; the comparison is relative to the largest entry of the analytic
// quantity, and every check reports how many entries it compared so that a
// test can assert it checked something.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <random>

namespace xshell::test {

struct DifferenceReport {
  double max_abs_error = 0.0;
  double scale = 0.0;  // largest |entry| of the analytic quantity
  int compared = 0;    // number of entries compared
  double relative_error() const { return max_abs_error / std::max(scale, 1e-300); }
};

// Compares an analytic gradient g(x) with central differences of f.
inline DifferenceReport check_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                       const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                       double h) {
  DifferenceReport r;
  r.scale = g.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const double fd = (f(xp) - f(xm)) / (2.0 * h);
    r.max_abs_error = std::max(r.max_abs_error, std::abs(fd - g[i]));
    ++r.compared;
  }
  return r;
}

// Compares an analytic Hessian with central differences of the gradient.
inline DifferenceReport check_hessian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& grad, const Eigen::VectorXd& x,
    const Eigen::MatrixXd& hessian, double h) {
  DifferenceReport r;
  r.scale = hessian.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const Eigen::VectorXd column = (grad(xp) - grad(xm)) / (2.0 * h);
    r.max_abs_error = std::max(r.max_abs_error, (column - hessian.col(i)).cwiseAbs().maxCoeff());
    r.compared += static_cast<int>(x.size());
  }
  return r;
}

inline Eigen::VectorXd random_vector(Eigen::Index n, std::mt19937& rng, double amplitude = 1.0) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

}  // namespace xshell::test
