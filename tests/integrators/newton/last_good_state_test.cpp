// Newton leaves the objective at the last good state when a step lands
// where the energy is not finite, even if the gradient is (KINSOL's line
// search watches only the gradient).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "integrators/newton/newton.hpp"

namespace xshell::test {

namespace {

// E = |x - 3|^2 / 2 with its exact gradient everywhere, but the energy is
// NaN wherever some x_i > 2: the Newton step from 0 lands at 3, where the
// gradient vanishes and the energy does not exist.
class NanEnergyBeyondTwo : public Objective {
 public:
  explicit NanEnergyBeyondTwo(int n) : x_(Eigen::VectorXd::Zero(n)), hessian_(n, n) {
    hessian_.setIdentity();
    hessian_.makeCompressed();
  }
  Eigen::Index size() const override { return x_.size(); }
  Eigen::VectorXd get() const override { return x_; }
  void set(const Eigen::VectorXd& q) override { x_ = q; }
  double energy() const override {
    if ((x_.array() > 2.0).any()) return std::numeric_limits<double>::quiet_NaN();
    return 0.5 * (x_.array() - 3.0).square().sum();
  }
  Eigen::VectorXd gradient() const override { return (x_.array() - 3.0).matrix(); }
  const Eigen::SparseMatrix<double>& hessian() override { return hessian_; }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(x_.size()); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(x_.size()); }

 private:
  Eigen::VectorXd x_;
  Eigen::SparseMatrix<double> hessian_;
};

}  // namespace

TEST_CASE(
    "Newton: a step to a finite gradient but a NaN energy is refused, the state before it kept") {
  NanEnergyBeyondTwo objective(3);
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  options.line_search = LineSearch::Kinsol;  // accepts the step on the gradient alone
  int reports = 0;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport&) { ++reports; };
  const NewtonResult result = solve_newton(objective, options, callbacks);
  INFO(result.reason);
  CHECK(result.status == SolveStatus::NonFinite);
  CHECK(result.iterations == 0);
  CHECK(reports == 1);  // the start only
  CHECK(objective.get() == Eigen::VectorXd::Zero(3));
  CHECK(std::isfinite(objective.energy()));
  CHECK(result.energy == doctest::Approx(13.5));
  CHECK(result.reason.find("not finite") != std::string::npos);
}

TEST_CASE("Newton with the energy line search backtracks away from a NaN energy") {
  NanEnergyBeyondTwo objective(3);
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  const NewtonResult result = solve_newton(objective, options);
  INFO(result.reason);
  CHECK_FALSE(result.converged());  // the minimum (3) is where the energy is NaN
  CHECK(std::isfinite(objective.energy()));
  CHECK((objective.get().array() <= 2.0).all());
  CHECK(objective.get().minCoeff() > 1.0);  // it did move towards the minimum
}

}  // namespace xshell::test
