#include "integrators/optimization/bounded_minimizer.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>

namespace xshell::test {

namespace {

BoundedProblem rosenbrock() {
  BoundedProblem problem;
  problem.start = Eigen::Vector2d(-1.2, 1.0);
  problem.lower = Eigen::Vector2d(-10, -10);
  problem.upper = Eigen::Vector2d(10, 10);
  problem.evaluate = [](const Eigen::VectorXd& p, double& f, Eigen::VectorXd& g) {
    const double a = 1 - p[0], b = p[1] - p[0] * p[0];
    f = a * a + 100 * b * b;
    g = Eigen::Vector2d(-2 * a - 400 * p[0] * b, 200 * b);
    return true;
  };
  return problem;
}

// (p0 - 3)^2 + (p1 + 1)^2 on [0, 2]^2: the minimum (2, 0) lies on two bounds.
BoundedProblem shifted_bowl() {
  BoundedProblem problem;
  problem.start = Eigen::Vector2d(1, 1);
  problem.lower = Eigen::Vector2d(0, 0);
  problem.upper = Eigen::Vector2d(2, 2);
  problem.evaluate = [](const Eigen::VectorXd& p, double& f, Eigen::VectorXd& g) {
    f = (p[0] - 3) * (p[0] - 3) + (p[1] + 1) * (p[1] + 1);
    g = Eigen::Vector2d(2 * (p[0] - 3), 2 * (p[1] + 1));
    return true;
  };
  return problem;
}

}  // namespace

TEST_CASE("Bounded minimization finds the Rosenbrock minimum with a progress line per iteration") {
  std::vector<MinimizerIteration> lines;
  MinimizerOptions options;
  options.max_iterations = 200;
  options.on_iteration = [&](const MinimizerIteration& it) { lines.push_back(it); };
  const MinimizerResult r = minimize_bounded(rosenbrock(), options);
  CHECK(r.status == MinimizerStatus::Converged);
  CHECK(r.p[0] == doctest::Approx(1.0).epsilon(1e-5));
  CHECK(r.p[1] == doctest::Approx(1.0).epsilon(1e-5));
  CHECK(r.objective < 1e-10);
  REQUIRE(lines.size() == std::size_t(r.iterations) + 1);
  for (std::size_t k = 0; k < lines.size(); ++k) CHECK(lines[k].iteration == int(k));
  CHECK(lines.front().objective == doctest::Approx(24.2));
  CHECK(r.evaluations >= r.iterations);
}

TEST_CASE("Bounded minimization stops on the active bounds") {
  const MinimizerResult r = minimize_bounded(shifted_bowl());
  CHECK(r.status == MinimizerStatus::Converged);
  CHECK(r.p[0] == doctest::Approx(2.0).epsilon(1e-6));
  CHECK(r.p[1] == doctest::Approx(0.0).scale(1.0).epsilon(1e-6));
  CHECK(r.objective == doctest::Approx(2.0).epsilon(1e-6));
}

TEST_CASE("Bounded minimization rejects points that cannot be evaluated and goes on") {
  // sum p^2, but points with p0 < 0.5 fail (as a design whose equilibrium
  // fails): the line search shortens its steps and the run ends in the
  // evaluable region, lower than it started, without an exception.
  BoundedProblem problem;
  problem.start = Eigen::Vector2d(2, 1);
  problem.lower = Eigen::Vector2d(-5, -5);
  problem.upper = Eigen::Vector2d(5, 5);
  int failures = 0;
  problem.evaluate = [&](const Eigen::VectorXd& p, double& f, Eigen::VectorXd& g) {
    if (p[0] < 0.5) return ++failures, false;
    f = p.squaredNorm();
    g = 2 * p;
    return true;
  };
  const MinimizerResult r = minimize_bounded(problem);
  CHECK(failures > 0);
  CHECK(r.p[0] >= 0.5);
  CHECK(r.objective < 5.0);
  CHECK(r.objective == doctest::Approx(r.p.squaredNorm()));
}

TEST_CASE("Bounded minimization fails cleanly when the start cannot be evaluated") {
  BoundedProblem problem = shifted_bowl();
  problem.evaluate = [](const Eigen::VectorXd&, double&, Eigen::VectorXd&) { return false; };
  const MinimizerResult r = minimize_bounded(problem);
  CHECK(r.status == MinimizerStatus::Failed);
  CHECK(r.p == problem.start);
  CHECK_FALSE(r.reason.empty());
}

TEST_CASE("Bounded minimization honours the stop flag and the iteration limit") {
  std::atomic<bool> stop{false};
  MinimizerOptions options;
  options.stop = &stop;
  options.on_iteration = [&](const MinimizerIteration& it) {
    if (it.iteration == 3) stop = true;
  };
  const MinimizerResult stopped = minimize_bounded(rosenbrock(), options);
  CHECK(stopped.status == MinimizerStatus::Interrupted);
  CHECK(stopped.iterations == 3);
  CHECK(std::string(minimizer_status_name(stopped.status)) == "interrupted");

  MinimizerOptions short_run;
  short_run.max_iterations = 4;
  const MinimizerResult limited = minimize_bounded(rosenbrock(), short_run);
  CHECK(limited.status == MinimizerStatus::IterationLimit);
  CHECK(limited.iterations == 4);
  CHECK(limited.objective < 24.2);
}

TEST_CASE("Bounded minimization refuses inconsistent bounds") {
  BoundedProblem problem = shifted_bowl();
  problem.start = Eigen::Vector2d(3, 1);
  CHECK_THROWS_AS(minimize_bounded(problem), std::invalid_argument);
  problem = shifted_bowl();
  problem.lower = Eigen::Vector3d(0, 0, 0);
  CHECK_THROWS_AS(minimize_bounded(problem), std::invalid_argument);
  problem = shifted_bowl();
  problem.lower[1] = 3;
  CHECK_THROWS_AS(minimize_bounded(problem), std::invalid_argument);
}

}  // namespace xshell::test
