#include "integrators/deployment/constrained_newton.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "finite_differences.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/deployment_fixtures.hpp"
#include "integrators/deployment/path_predictor.hpp"
#include "integrators/toy_objectives.hpp"

namespace xshell::test {

namespace {

// R R^T + I for a random R (n x n): symmetric positive definite.
Eigen::MatrixXd random_stiffness(int n) {
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
  return R * R.transpose() + Eigen::MatrixXd::Identity(n, n);
}

// The average of unknowns 1, 2, 4 and 5 of n >= 6 (a tree 1-2, 1-4, 4-5).
AverageConstraint average_of_four(int n) {
  return AverageConstraint(n, {1, 2, 4, 5}, {-1, 0, 0, 1}, 4, 0.0);
}

// The quadratic with a gradient that round-off spoils: every entry off by
// +/- delta, its sign a fine-grained function of q, so that no iterate can
// bring the gradient measure below about delta (its round-off floor).
class NoisyQuadratic : public Quadratic {
 public:
  NoisyQuadratic(const Eigen::MatrixXd& K, const Eigen::VectorXd& f, double delta)
      : Quadratic(K, f), delta_(delta) {}
  Eigen::VectorXd gradient() const override {
    Eigen::VectorXd g = Quadratic::gradient();
    const Eigen::VectorXd q = get();
    for (Eigen::Index i = 0; i < g.size(); ++i)
      g[i] += std::sin(1e9 * q[i] + static_cast<double>(i)) > 0.0 ? delta_ : -delta_;
    return g;
  }

 private:
  double delta_;
};

// Two averaged unknowns u, v (A = (u + v) / 2) and w:
//   E = (u - v)^2 + (w^2 - A)^2 + A^2.
// For A > 0, w = 0 is a saddle (d2E/dw2 = -4A) and the minima are w = +/- sqrt(A),
// where E = A^2 and the torque dE/dA = 2A; at the saddle E = 2A^2, torque 4A.
class Buckling : public Objective {
 public:
  Eigen::Index size() const override { return 3; }
  Eigen::VectorXd get() const override { return q_; }
  void set(const Eigen::VectorXd& q) override { q_ = q; }
  double energy() const override {
    const double u = q_[0], v = q_[1], w = q_[2], A = 0.5 * (u + v);
    return (u - v) * (u - v) + (w * w - A) * (w * w - A) + A * A;
  }
  Eigen::VectorXd gradient() const override {
    const double u = q_[0], v = q_[1], w = q_[2], A = 0.5 * (u + v), r = w * w - A;
    const double dA = -2.0 * r + 2.0 * A;  // dE/dA at fixed u - v
    return Eigen::Vector3d(2.0 * (u - v) + 0.5 * dA, -2.0 * (u - v) + 0.5 * dA, 4.0 * w * r);
  }
  const Eigen::SparseMatrix<double>& hessian() override {
    const double w = q_[2], A = 0.5 * (q_[0] + q_[1]);
    Eigen::Matrix3d H;
    // d2/dA2 of r^2 + A^2 is 4; u, v enter A with weight 1/2.
    const double aa = 0.25 * 4.0, aw = 0.5 * (-4.0 * w);
    H << 2.0 + aa, -2.0 + aa, aw,  //
        -2.0 + aa, 2.0 + aa, aw,   //
        aw, aw, 12.0 * w * w - 4.0 * A;
    H_ = H.sparseView(0.0, 0.0);
    return H_;
  }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(3); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(3); }

 private:
  Eigen::VectorXd q_ = Eigen::Vector3d(0.5, 0.5, 0.0);
  Eigen::SparseMatrix<double> H_;
};

// Buckling with a stiff unknown y that the mode bends at second order:
//   E = (u - v)^2 + K (y - w^2)^2 + (w^2 - A)^2 + A^2,
// the same saddle (w = y = 0) and minima (w = +/- sqrt(A), y = A), now at
// the ends of a parabolic valley: along the straight line in w the energy
// stays above 2 A^2 - A^2 / (K + 1).
class BentBuckling : public Objective {
 public:
  static constexpr double K = 100.0;
  Eigen::Index size() const override { return 4; }
  Eigen::VectorXd get() const override { return q_; }
  void set(const Eigen::VectorXd& q) override { q_ = q; }
  double energy() const override {
    const double d = q_[0] - q_[1], A = 0.5 * (q_[0] + q_[1]), w = q_[2];
    const double r = w * w - A, s = q_[3] - w * w;
    return d * d + K * s * s + r * r + A * A;
  }
  Eigen::VectorXd gradient() const override {
    const double d = q_[0] - q_[1], A = 0.5 * (q_[0] + q_[1]), w = q_[2];
    const double r = w * w - A, s = q_[3] - w * w, dA = -2.0 * r + 2.0 * A;
    return Eigen::Vector4d(2.0 * d + 0.5 * dA, -2.0 * d + 0.5 * dA, 4.0 * w * r - 4.0 * K * w * s,
                           2.0 * K * s);
  }
  const Eigen::SparseMatrix<double>& hessian() override {
    const double A = 0.5 * (q_[0] + q_[1]), w = q_[2], r = w * w - A, s = q_[3] - w * w;
    const double aw = 0.5 * (-4.0 * w);
    const double ww = 4.0 * r + 8.0 * w * w - 4.0 * K * s + 8.0 * K * w * w;
    Eigen::Matrix4d H;
    H << 3.0, -1.0, aw, 0.0,  //
        -1.0, 3.0, aw, 0.0,   //
        aw, aw, ww, -4.0 * K * w, 0.0, 0.0, -4.0 * K * w, 2.0 * K;
    H_ = H.sparseView(0.0, 0.0);
    return H_;
  }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(4); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(4); }

 private:
  Eigen::VectorXd q_ = Eigen::Vector4d(0.5, 0.5, 0.0, 0.0);
  Eigen::SparseMatrix<double> H_;
};

// Two averaged unknowns u, v (A = (u + v) / 2) and w, a curved path:
//   E = (u - v)^2 + (w - A^2)^2 + s A^2,
// whose constrained equilibrium at A is u = v = A, w = A^2: q''(A) =
// (0, 0, 2). Along the path, H restricted to (A, w) has the Schur
// complement 2 s: H is positive definite for s > 0, indefinite for s < 0,
// where B^T H B (in u - v and w) stays positive definite.
class Parabola : public Objective {
 public:
  explicit Parabola(double s) : s_(s) {}
  Eigen::Index size() const override { return 3; }
  Eigen::VectorXd get() const override { return q_; }
  void set(const Eigen::VectorXd& q) override { q_ = q; }
  double energy() const override {
    const double d = q_[0] - q_[1], A = 0.5 * (q_[0] + q_[1]), r = q_[2] - A * A;
    return d * d + r * r + s_ * A * A;
  }
  Eigen::VectorXd gradient() const override {
    const double d = q_[0] - q_[1], A = 0.5 * (q_[0] + q_[1]), r = q_[2] - A * A;
    const double dA = -4.0 * A * r + 2.0 * s_ * A;
    return Eigen::Vector3d(0.5 * dA + 2.0 * d, 0.5 * dA - 2.0 * d, 2.0 * r);
  }
  const Eigen::SparseMatrix<double>& hessian() override {
    const double A = 0.5 * (q_[0] + q_[1]), r = q_[2] - A * A;
    const double AA = 0.25 * (-4.0 * r + 8.0 * A * A + 2.0 * s_), Aw = 0.5 * (-4.0 * A);
    Eigen::Matrix3d H;
    H << AA + 2.0, AA - 2.0, Aw,  //
        AA - 2.0, AA + 2.0, Aw,   //
        Aw, Aw, 2.0;
    H_ = H.sparseView(0.0, 0.0);
    return H_;
  }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(3); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(3); }

 private:
  double s_;
  Eigen::VectorXd q_ = Eigen::Vector3d(0.3, 0.2, 0.1);
  Eigen::SparseMatrix<double> H_;
};

// Solution (q, tau) of grad E = tau a, a.q = A for the quadratic, densely.
std::pair<Eigen::VectorXd, double> kkt(const Eigen::MatrixXd& K, const Eigen::VectorXd& f,
                                       const Eigen::VectorXd& a, double A) {
  const Eigen::Index n = K.rows();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 1, n + 1);
  M.topLeftCorner(n, n) = K;
  M.topRightCorner(n, 1) = -a;
  M.bottomLeftCorner(1, n) = a.transpose();
  Eigen::VectorXd rhs(n + 1);
  rhs << f, A;
  const Eigen::VectorXd x = M.fullPivLu().solve(rhs);
  return {x.head(n), x[n]};
}

}  // namespace

TEST_CASE(
    "Constrained Newton: the Schur complement solves a quadratic in one step, with its "
    "multiplier") {
  std::mt19937 rng(3);
  int cases = 0;
  for (bool definite : {true, false}) {
    CAPTURE(definite);
    const int n = 7;
    Eigen::MatrixXd K = random_stiffness(n);
    // Indefinite along the averaged direction only: K - c a a^T stays
    // positive definite on the constraint's plane (a.q = const).
    const AverageConstraint c = average_of_four(n);
    if (!definite) K -= 60.0 * c.coefficients() * c.coefficients().transpose() * 16.0;
    const Eigen::VectorXd f = random_vector(n, rng);
    Quadratic objective(K, f);
    ConstrainedNewtonSolver solver(objective, c, NewtonOptions{});
    const ConstrainedNewtonResult r = solver.solve(0.3);
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    CHECK(r.iterations == 1);
    CHECK(r.stable);
    CHECK(r.schur_iterations == (definite ? 1 : 0));
    CHECK(r.null_space_iterations == (definite ? 0 : 1));
    const auto [q, tau] = kkt(K, f, c.coefficients(), 0.3);
    CHECK((objective.get() - q).norm() < 1e-10 * q.norm());
    CHECK(r.multiplier == doctest::Approx(tau).epsilon(1e-9));
    CHECK(c.value(objective.get()) == doctest::Approx(0.3).epsilon(1e-14));
    // The path's tangent dq/dA: the KKT solution's derivative in A, from
    // the stability test's factorization (H when definite, else B^T H B).
    const long factorizations = solver.factorizations();
    const Eigen::VectorXd t = solver.tangent();
    CHECK(solver.factorizations() == factorizations);
    const Eigen::VectorXd exact = (kkt(K, f, c.coefficients(), 0.3 + 1e-3).first -
                                   kkt(K, f, c.coefficients(), 0.3 - 1e-3).first) /
                                  2e-3;
    CHECK((t - exact).norm() < 1e-8 * exact.norm());
    CHECK(c.coefficients().dot(t) == doctest::Approx(1.0).epsilon(1e-12));
    // The adjoint lambda: [K a; a^T 0] [lambda; mu] = [f; 0].
    const Eigen::VectorXd rhs = random_vector(n, rng);
    const Eigen::VectorXd lambda = solver.adjoint(rhs);
    const Eigen::VectorXd dense = kkt(K, rhs, c.coefficients(), 0.0).first;
    REQUIRE(lambda.size() == n);
    CHECK((lambda - dense).norm() < 1e-10 * dense.norm());
    CHECK(std::abs(c.coefficients().dot(lambda)) < 1e-12 * lambda.norm());
    ++cases;
  }
  CHECK(cases == 2);
}

TEST_CASE(
    "Constrained Newton: a solution far beyond max_step is reached in capped steps of doubling "
    "length") {
  std::mt19937 rng(11);
  const int n = 7;
  const Eigen::MatrixXd K = random_stiffness(n);
  const AverageConstraint c = average_of_four(n);
  Eigen::VectorXd f = random_vector(n, rng);
  const auto [q, tau] = kkt(K, f, c.coefficients(), 0.3);
  // The solution is linear in (f, A): scaled, it lies 1000 steps of
  // max_step away.
  const double scale = 1000.0 / q.norm(), target = 0.3 * scale;
  f *= scale;
  const auto [far, far_tau] = kkt(K, f, c.coefficients(), target);
  REQUIRE(far.norm() == doctest::Approx(1000.0).epsilon(1e-9));
  Quadratic objective(K, f);
  NewtonOptions options;
  options.max_step = 1.0;
  options.grow_step_cap = true;
  ConstrainedNewtonSolver solver(objective, c, options);
  std::vector<double> steps;  // 2-norm of each step
  const ConstrainedNewtonResult r = solver.solve(target, recording_step_lengths(objective, steps));
  CAPTURE(r.reason);
  REQUIRE(r.converged());
  // A fixed cap would take 1000 steps; doubling it, about log2(1000) = 10.
  CHECK(r.iterations <= 13);
  REQUIRE(steps.size() >= 3);
  // Capped at max_step, taken in full, then at twice that, ...
  CHECK(steps[0] == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(steps[1] == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(steps[2] == doctest::Approx(4.0).epsilon(1e-12));
  CHECK((objective.get() - far).norm() < 1e-9 * far.norm());
  // Without grow_step_cap, every step is capped at max_step: 1000 steps
  // needed, more than the solve's iteration limit.
  options.grow_step_cap = false;
  objective.set(Eigen::VectorXd::Zero(n));
  ConstrainedNewtonSolver fixed(objective, c, options);
  const ConstrainedNewtonResult capped = fixed.solve(target);
  CHECK(!capped.converged());
  CHECK(capped.iterations == options.max_iterations);
  CHECK((objective.get() - far).norm() > 0.5 * far.norm());
}

TEST_CASE("Constrained Newton leaves a symmetric saddle along negative curvature, or reports it") {
  int cases = 0;
  for (int escapes : {0, 2}) {
    CAPTURE(escapes);
    Buckling objective;
    const AverageConstraint c(3, {0, 1}, {-1, 0}, 2, 0.0);
    NewtonOptions options;
    options.gradient_tolerance = 1e-12;
    ConstrainedNewtonSolver solver(objective, c, options);
    solver.max_saddle_escapes = escapes;
    const ConstrainedNewtonResult r = solver.solve(1.0);  // from A = 0.5, w = 0
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    const Eigen::VectorXd q = objective.get();
    if (escapes == 0) {
      CHECK_FALSE(r.stable);  // the saddle w = 0, reported as such
      CHECK(q[2] == 0.0);
      CHECK(r.energy == doctest::Approx(2.0));
      CHECK(r.multiplier == doctest::Approx(4.0));
      CHECK(r.saddle_escapes == 0);
    } else {
      CHECK(r.stable);
      CHECK(r.saddle_escapes == 1);
      CHECK(q[2] == doctest::Approx(1.0).epsilon(1e-10));  // the side of the positive largest entry
      CHECK(r.energy == doctest::Approx(1.0));
      CHECK(r.multiplier == doctest::Approx(2.0).epsilon(1e-9));
    }
    CHECK(0.5 * (q[0] + q[1]) == doctest::Approx(1.0).epsilon(1e-14));
    ++cases;
  }
  CHECK(cases == 2);
}

TEST_CASE("Constrained Newton's escape from a saddle follows the bent branch to its well") {
  BentBuckling objective;
  const AverageConstraint c(4, {0, 1}, {-1, 0}, 2, 0.0);
  NewtonOptions options;
  options.gradient_tolerance = 1e-12;
  ConstrainedNewtonSolver solver(objective, c, options);
  solver.max_saddle_escapes = 1;
  Eigen::VectorXd escaped_to;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport&) {
    if (escaped_to.size() == 0 && objective.get()[2] != 0.0) escaped_to = objective.get();
  };
  const ConstrainedNewtonResult r = solver.solve(1.0, callbacks);  // the saddle at A = 1
  CAPTURE(r.reason);
  REQUIRE(r.converged());
  CHECK(r.stable);
  CHECK(r.saddle_escapes == 1);
  REQUIRE(escaped_to.size() == 4);
  // The straight line stops at |w| = (K + 1)^-1/2, about 0.1; the bend
  // y ~ w^2 reaches the well's neighbourhood in the escape itself.
  CHECK(std::abs(escaped_to[2]) > 0.9);
  CHECK(escaped_to[3] == doctest::Approx(escaped_to[2] * escaped_to[2]).epsilon(0.05));
  CHECK(std::abs(objective.get()[2]) == doctest::Approx(1.0).epsilon(1e-10));
  CHECK(objective.get()[3] == doctest::Approx(1.0).epsilon(1e-10));
  CHECK(r.energy == doctest::Approx(1.0));
}

TEST_CASE("Constrained Newton leaves a saddle it converges to linearly before reaching it") {
  // At A = 1 and w = 0 the shifted steps bring u - v to 0 linearly and
  // never move w (its gradient is 0 there): they converge to the saddle.
  Buckling objective;
  objective.set(Eigen::Vector3d(1.3, 0.7, 0.0));
  const AverageConstraint c(3, {0, 1}, {-1, 0}, 2, 0.0);
  NewtonOptions options;
  options.gradient_tolerance = 1e-12;
  ConstrainedNewtonSolver solver(objective, c, options);
  solver.max_saddle_escapes = 1;
  double measure_before_escape = -1.0, last_measure = 0.0;
  int shifted_before_escape = 0;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport& report) {
    if (measure_before_escape < 0.0 && objective.get()[2] != 0.0)
      measure_before_escape = last_measure;
    if (measure_before_escape < 0.0 && report.shifted) ++shifted_before_escape;
    last_measure = report.gradient_measure;
  };
  const ConstrainedNewtonResult r = solver.solve(1.0, callbacks);
  CAPTURE(r.reason);
  REQUIRE(r.converged());
  CHECK(r.stable);
  CHECK(r.saddle_escapes == 1);
  CHECK(objective.get()[2] == doctest::Approx(1.0).epsilon(1e-10));
  // Left after a few linear steps, far above the tolerance.
  CHECK(shifted_before_escape >= 2);
  CHECK(measure_before_escape > 1e3 * options.gradient_tolerance);
  REQUIRE(r.saddles_escaped.size() == 1);
  CHECK(r.saddles_escaped[0].lowest_eigenvalue < 0.0);
}

TEST_CASE(
    "Constrained Newton stops at a round-off floor within twice the tolerance, and fails above "
    "it") {
  std::mt19937 rng(5);
  const int n = 7;
  const Eigen::MatrixXd K = random_stiffness(n);
  const AverageConstraint c = average_of_four(n);
  const Eigen::VectorXd f = 100.0 * random_vector(n, rng);
  int cases = 0;
  for (double delta : {0.7e-6, 5e-6}) {
    CAPTURE(delta);
    NoisyQuadratic objective(K, f, delta);
    NewtonOptions options;  // gradient tolerance 1e-6
    ConstrainedNewtonSolver solver(objective, c, options);
    const ConstrainedNewtonResult r = solver.solve(0.3);
    CAPTURE(r.reason);
    CHECK(r.gradient_measure > options.gradient_tolerance);
    if (delta < options.gradient_tolerance) {
      CHECK(r.converged());
      CHECK(r.at_round_off_floor);
      CHECK(r.gradient_measure <= 2.0 * options.gradient_tolerance);
      CHECK(r.reason.find("round-off floor") != std::string::npos);
    } else {
      CHECK(r.status == SolveStatus::LineSearchFailed);
      CHECK_FALSE(r.at_round_off_floor);
    }
    CHECK(r.iterations < 20);
    ++cases;
  }
  CHECK(cases == 2);
}

TEST_CASE(
    "Constrained Newton: the path's second derivative from the tangent's factorization, H "
    "definite or not") {
  int cases = 0;
  for (double s : {1.0, -10.0}) {
    CAPTURE(s);
    Parabola objective(s);
    const AverageConstraint c(3, {0, 1}, {-1, 0}, 2, 0.0);
    NewtonOptions options;
    options.gradient_tolerance = 1e-12;
    ConstrainedNewtonSolver solver(objective, c, options);
    const double A = 0.5;
    const ConstrainedNewtonResult r = solver.solve(A);
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    CHECK((objective.get() - Eigen::Vector3d(A, A, A * A)).norm() < 1e-9);
    CHECK(r.schur_iterations == (s > 0.0 ? r.iterations : 0));
    const long factorizations = solver.factorizations();
    const Eigen::VectorXd t = solver.tangent();
    REQUIRE(t.size() == 3);
    CHECK((t - Eigen::Vector3d(1.0, 1.0, 2.0 * A)).norm() < 1e-8);
    // The gradient is cubic along a line: its central second difference
    // is exact up to round-off.
    const Eigen::VectorXd q = objective.get();
    const Eigen::VectorXd third = gradient_second_difference(
        [&](const Eigen::VectorXd& x) {
          objective.set(x);
          return objective.gradient();
        },
        q, t, 1e-3);
    CHECK(objective.get() == q);
    const Eigen::VectorXd k = solver.second_derivative(third);
    REQUIRE(k.size() == 3);
    CHECK((k - Eigen::Vector3d(0.0, 0.0, 2.0)).norm() < 1e-6);
    CHECK(std::abs(c.coefficients().dot(k)) < 1e-12);
    CHECK(solver.factorizations() == factorizations);
    // The next solve's factorizations replace the tangent's.
    REQUIRE(solver.solve(A + 0.1).converged());
    CHECK(solver.second_derivative(third).size() == 0);
    ++cases;
  }
  CHECK(cases == 2);
}

TEST_CASE(
    "Constrained Newton on a mechanism: the opening mode is free, the constrained problem stable") {
  LinkageProblem problem = flat_mechanism(3);
  LinkageObjective objective(problem);
  const AverageConstraint c = average_opening_angle_constraint(problem);
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  ConstrainedNewtonSolver solver(objective, c, options);
  const double target = c.value(problem.free_dofs()) + 0.3;
  Eigen::VectorXd q = problem.free_dofs();
  c.project(q, target);
  problem.set_free_dofs(q);
  const ConstrainedNewtonResult r = solver.solve(target);
  CAPTURE(r.reason);
  REQUIRE(r.converged());
  // H is singular (up to round-off): LL^T may or may not succeed, and either
  // step then converges.
  CHECK(r.schur_iterations + r.null_space_iterations == r.iterations);
  CHECK(r.stable);
  CHECK(std::abs(r.multiplier) < 1e-9);
  CHECK(problem.energy().total() < 1e-12);
}

// Every rod edge of the linkage, segment by segment.
std::vector<Eigen::Vector3d> all_edges(const LinkageProblem& problem) {
  std::vector<Eigen::Vector3d> out;
  const RodLinkage& l = problem.linkage();
  for (int s = 0; s < l.num_segments(); ++s)
    for (int j = 0; j < l.segment(s).num_edges(); ++j) out.push_back(l.segment(s).edge(j));
  return out;
}

// max |e_after - e_before| / l over the edges.
double largest_relative_change(const LinkageProblem& problem,
                               const std::vector<Eigen::Vector3d>& before,
                               const std::vector<Eigen::Vector3d>& after) {
  double out = 0.0;
  size_t i = 0;
  const RodLinkage& l = problem.linkage();
  for (int s = 0; s < l.num_segments(); ++s)
    for (double rest : l.segment(s).rest_lengths()) {
      out = std::max(out, (after[i] - before[i]).norm() / rest);
      ++i;
    }
  return out;
}

TEST_CASE(
    "Constrained Newton: the mixed Hessian after steps along the curve, the same equilibrium") {
  int mixed_steps = 0, shifted_steps = 0, kept_exact = 0;
  std::vector<Eigen::Vector3d> end[2];
  double energy[2] = {0.0, 0.0};
  for (bool mixed : {false, true}) {
    CAPTURE(mixed);
    // The dome from a crumpled start: shifted steps (on the line) first.
    LinkageProblem problem = dome_problem(3, 0.8);
    std::mt19937 rng(11);
    problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05));
    LinkageObjective objective(problem);
    const AverageConstraint c = average_opening_angle_constraint(problem);
    NewtonOptions options;
    options.gradient_tolerance = 1e-10;
    options.mixed_hessian = mixed;
    ConstrainedNewtonSolver solver(objective, c, options);
    NewtonCallbacks callbacks;
    std::vector<Eigen::Vector3d> edges = all_edges(problem);
    callbacks.on_iteration = [&](const NewtonReport& r) {
      const std::vector<Eigen::Vector3d> before = std::exchange(edges, all_edges(problem));
      if (r.iteration == 0) return;
      // Unshifted steps follow the curve; shifted ones (and escapes) the
      // line. A step that changed no edge by 1e-4 of its length leaves the
      // Hessian exact (LinkageProblem::kNegligibleEdgeChange).
      const bool negligible = largest_relative_change(problem, before, edges) < 2e-4;
      if (!negligible) CHECK(problem.mixed_hessian() == (mixed && !r.shifted));
      if (problem.mixed_hessian()) CHECK(!negligible);
      kept_exact += mixed && !r.shifted && !problem.mixed_hessian() ? 1 : 0;
      mixed_steps += problem.mixed_hessian() ? 1 : 0;
      shifted_steps += r.shifted ? 1 : 0;
    };
    const ConstrainedNewtonResult r = solver.solve(c.value(problem.free_dofs()) + 0.4, callbacks);
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    CHECK(r.stable);
    CHECK(!problem.mixed_hessian());  // the exact one for the tangent
    end[mixed] = problem.vertex_positions();
    energy[mixed] = problem.energy().total();
  }
  MESSAGE(mixed_steps << " mixed steps, " << shifted_steps << " shifted, " << kept_exact
                      << " unshifted steps too short to mix");
  CHECK(mixed_steps > 0);
  CHECK(kept_exact > 0);  // the last steps, converging
  CHECK(energy[1] == doctest::Approx(energy[0]).epsilon(1e-9));
  for (size_t v = 0; v < end[0].size(); ++v) CHECK((end[1][v] - end[0][v]).norm() < 1e-7);
}

}  // namespace xshell::test
