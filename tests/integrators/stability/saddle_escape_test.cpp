// Leaving saddles (integrators/stability/saddle_escape.hpp) in the solvers:
// a column compressed beyond Euler's load, relaxed from straight, where
// Newton and damped dynamics both stop on the straight saddle without the
// escape; a double well whose third unknown is a mechanism.
#include "integrators/stability/saddle_escape.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "integrators/common/linkage_objective.hpp"
#include "integrators/deployment/deployment_fixtures.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/elastica.hpp"
#include "integrators/newton/newton.hpp"
#include "integrators/stability/branch_bias.hpp"

namespace xshell::test {

namespace {

// Clamped-free column of length 1 along x under the axial load P at its
// tip, exactly straight. Rectangle w x 1.2 w, the weak bending stiffness
// E I = 1 (E = 12 / (w^3 1.2 w)): one buckling plane, not a double
// eigenvalue. Unit mass per length.
LinkageProblem straight_column(double load,
                               const Eigen::Vector3d& axis = Eigen::Vector3d::UnitX()) {
  LineGraph g;
  g.vertices = {{0, 0, 0}, axis};
  g.edges = {{0, 1}};
  LinkageOptions o;
  o.subdivisions = 40;
  o.rest_shape = RestShape::Straight;
  const double w = 0.01, h = 1.2 * w;
  o.material.young_modulus = 12.0 / (w * w * w * h);
  o.material.density = 1.0 / (w * h);
  o.material.section = {SectionShape::Rectangle, w, h};
  StaticsSetup s;
  s.supports = {{0, {SupportDof::Orientation}}};
  s.forces = {{1, -load * axis}};
  o.clamped_ends = clamped_free_ends(g, s.supports);
  return LinkageProblem(RodLinkage(g, o), s);
}

constexpr double kCritical = M_PI * M_PI / 4.0;  // clamped-free, E I = 1, L = 1
constexpr double kLoad = 1.2 * kCritical;

NewtonOptions newton_options(const LinkageProblem& problem, const Eigen::Vector3d& direction) {
  NewtonOptions n;
  n.gradient_tolerance = 1e-9;
  n.max_iterations = 200;
  n.escape.bias = branch_bias(problem, direction);
  return n;
}

}  // namespace

TEST_CASE("Newton leaves the straight column's saddle and buckles to the side asked for") {
  const double expected = postbuckled_tip_deflection(kLoad / kCritical);  // L = 1
  const Eigen::Vector3d diagonal(0.0, 1.0, 1.0);  // not normal to the buckling plane
  int checked = 0;
  for (double side : {1.0, -1.0}) {
    CAPTURE(side);
    LinkageProblem column = straight_column(kLoad);
    LinkageObjective objective(column);
    const double straight_energy = column.energy().total();
    const NewtonResult r = solve_newton(objective, newton_options(column, side * diagonal));
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    CHECK(r.stable);
    REQUIRE(r.saddles_escaped.size() == 1);
    CHECK(r.saddles_escaped[0].lowest_eigenvalue < 0.0);
    CHECK(r.saddles_escaped[0].step == -1);
    CHECK(r.energy < r.saddles_escaped[0].energy);
    CHECK(r.saddles_escaped[0].energy < straight_energy);  // the straight state, shortened
    const Eigen::Vector3d tip = column.vertex_positions()[1];
    const double lateral = std::hypot(tip.y(), tip.z());
    CHECK(lateral == doctest::Approx(expected).epsilon(0.005));
    CHECK(side * diagonal.dot(tip) > 0.1 * lateral);  // the side of the buckling direction
    ++checked;
  }
  CHECK(checked == 2);
}

TEST_CASE("With the escape off, Newton reports the column's saddle") {
  LinkageProblem column = straight_column(kLoad);
  LinkageObjective objective(column);
  NewtonOptions n = newton_options(column, Eigen::Vector3d::UnitZ());
  n.escape.enabled = false;
  const NewtonResult r = solve_newton(objective, n);
  REQUIRE(r.converged());
  CHECK_FALSE(r.stable);
  CHECK(r.saddles_escaped.empty());
  CHECK(column.vertex_positions()[1].tail<2>().norm() < 1e-12);
}

TEST_CASE("Damped dynamics from the column's saddle reaches Newton's buckled state") {
  // The saddle, by Newton with the escape off; then Newton and dynamics
  // leave it, both towards `direction`.
  const Eigen::Vector3d direction(0.0, -1.0, 1.0);
  LinkageProblem by_newton = straight_column(kLoad);
  LinkageObjective newton_objective(by_newton);
  NewtonOptions n = newton_options(by_newton, direction);
  n.escape.enabled = false;
  REQUIRE(solve_newton(newton_objective, n).converged());
  LinkageProblem by_dynamics = by_newton;
  LinkageObjective dynamics_objective(by_dynamics);
  n.escape.enabled = true;
  const NewtonResult rn = solve_newton(newton_objective, n);
  REQUIRE(rn.converged());
  REQUIRE(rn.stable);
  REQUIRE(rn.saddles_escaped.size() == 1);
  DynamicsOptions d;
  d.stopping.gradient_tolerance = 1e-9;
  d.stopping.max_steps = 20000;
  d.escape.bias = branch_bias(by_dynamics, direction);
  long last_step = -1;
  bool increasing = true;
  DynamicsCallbacks callbacks;
  callbacks.on_step = [&](const DynamicsReport& r) {
    increasing = increasing && r.step > last_step;
    last_step = r.step;
  };
  const DynamicsResult rd = solve_dynamics(dynamics_objective, d, callbacks);
  CAPTURE(rd.reason);
  REQUIRE(rd.converged());
  CHECK(rd.stable);
  REQUIRE(rd.saddles_escaped.size() == 1);
  CHECK(rd.saddles_escaped[0].lowest_eigenvalue ==
        doctest::Approx(rn.saddles_escaped[0].lowest_eigenvalue).epsilon(1e-6));
  CHECK(increasing);  // the steps after the escape are numbered on
  CHECK(last_step == rd.iterations);
  const Eigen::Vector3d tn = by_newton.vertex_positions()[1];
  const Eigen::Vector3d td = by_dynamics.vertex_positions()[1];
  CHECK(direction.dot(tn) > 0.0);
  CHECK((tn - td).norm() <= 1e-6);
  CHECK(rd.energy == doctest::Approx(rn.energy).epsilon(1e-9));
}

TEST_CASE("Damped dynamics from the straight column buckles to the side asked for, both ways") {
  // From straight, not from the converged saddle: the unstable mode grows
  // during the run, from whatever seeds it (a column not along an axis has
  // round-off in every coordinate).
  const double expected = postbuckled_tip_deflection(kLoad / kCritical);
  const Eigen::Vector3d axis = Eigen::Vector3d(0.6, 0.7, 0.3).normalized();
  const Eigen::Vector3d diagonal = axis.cross(Eigen::Vector3d(0.2, -0.4, 1.0)).normalized();
  int checked = 0;
  for (double side : {1.0, -1.0}) {
    CAPTURE(side);
    LinkageProblem column = straight_column(kLoad, axis);
    LinkageObjective objective(column);
    DynamicsOptions d;
    d.stopping.gradient_tolerance = 1e-9;
    d.stopping.max_steps = 20000;
    d.escape.bias = branch_bias(column, side * diagonal);
    const DynamicsResult r = solve_dynamics(objective, d);
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    CHECK(r.stable);
    const Eigen::Vector3d tip = column.vertex_positions()[1];
    const double lateral = (tip - tip.dot(axis) * axis).norm();
    CHECK(lateral == doctest::Approx(expected).epsilon(0.005));
    CHECK(side * diagonal.dot(tip) > 0.1 * lateral);
    ++checked;
  }
  CHECK(checked == 2);
}

namespace {

// E = (x^2 - 1)^2 + y^2 + 0 z: a saddle at x = 0 between the wells x = +-1,
// and z a mechanism (a zero mode everywhere).
class DoubleWell : public Objective {
 public:
  explicit DoubleWell(Eigen::Vector3d q) : q_(q) {}
  Eigen::Index size() const override { return 3; }
  Eigen::VectorXd get() const override { return q_; }
  void set(const Eigen::VectorXd& q) override { q_ = q; }
  double energy() const override {
    const double x = q_[0], y = q_[1];
    return (x * x - 1.0) * (x * x - 1.0) + y * y;
  }
  Eigen::VectorXd gradient() const override {
    const double x = q_[0], y = q_[1];
    return Eigen::Vector3d(4.0 * x * (x * x - 1.0), 2.0 * y, 0.0);
  }
  const Eigen::SparseMatrix<double>& hessian() override {
    std::vector<Eigen::Triplet<double>> entries = {
        {0, 0, 12.0 * q_[0] * q_[0] - 4.0}, {1, 1, 2.0}, {2, 2, 0.0}};
    H_.resize(3, 3);
    H_.setFromTriplets(entries.begin(), entries.end());
    return H_;
  }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(3); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(3); }

 private:
  Eigen::Vector3d q_;
  Eigen::SparseMatrix<double> H_;
};

// E = K (y - x^2)^2 + (x^2 - 1)^2: a saddle at the origin (curvature -4
// along x, 2K along y) between the minima (+-1, 1), at the ends of a
// parabolic valley. Along the straight line (t, 0) the stiff term rises as
// K t^4: its lowest energy is 1 - 1 / (K + 1), at |t| = (K + 1)^-1/2.
class CurvedValley : public Objective {
 public:
  static constexpr double K = 100.0;
  Eigen::Index size() const override { return 2; }
  Eigen::VectorXd get() const override { return q_; }
  void set(const Eigen::VectorXd& q) override { q_ = q; }
  double energy() const override {
    const double x = q_[0], s = q_[1] - x * x, r = x * x - 1.0;
    return K * s * s + r * r;
  }
  Eigen::VectorXd gradient() const override {
    const double x = q_[0], s = q_[1] - x * x, r = x * x - 1.0;
    return Eigen::Vector2d(-4.0 * K * x * s + 4.0 * x * r, 2.0 * K * s);
  }
  const Eigen::SparseMatrix<double>& hessian() override {
    const double x = q_[0], s = q_[1] - x * x, r = x * x - 1.0;
    Eigen::Matrix2d H;
    H << -4.0 * K * s + 8.0 * K * x * x + 4.0 * r + 8.0 * x * x, -4.0 * K * x,  //
        -4.0 * K * x, 2.0 * K;
    H_ = H.sparseView(0.0, 0.0);
    return H_;
  }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(2); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(2); }

 private:
  Eigen::Vector2d q_ = Eigen::Vector2d::Zero();
  Eigen::SparseMatrix<double> H_;
};

}  // namespace

TEST_CASE("The escape from a saddle follows the curved valley to second order") {
  CurvedValley valley;
  CholeskySolver solver;
  const EscapeResult left =
      escape_saddle(valley, valley.hessian(), valley.mass(), solver, SaddleEscapeOptions{});
  REQUIRE(left.outcome == EscapeOutcome::Escaped);
  CHECK(left.saddle.lowest_eigenvalue == doctest::Approx(-4.0).epsilon(1e-9));
  const double x = valley.get()[0], y = valley.get()[1];
  // Along the straight line no energy below 1 - 1 / (K + 1) (|x| = 0.1):
  // the bend (y ~ x^2, its coefficient 2K / (2K + 8)) reaches the wells.
  CHECK(valley.energy() < 0.5);
  CHECK(std::abs(x) > 0.9);
  CHECK(y == doctest::Approx(x * x * 2.0 * CurvedValley::K / (2.0 * CurvedValley::K + 8.0)));
  const NewtonResult r = solve_newton(valley, NewtonOptions{});
  REQUIRE(r.converged());
  CHECK(r.stable);
  CHECK(std::abs(valley.get()[0]) == doctest::Approx(1.0).epsilon(1e-6));
  CHECK(valley.get()[1] == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE("Newton leaves a saddle on the side of the bias, and never a mechanism's zero mode") {
  int checked = 0;
  for (double side : {1.0, -1.0, 0.0}) {
    CAPTURE(side);
    DoubleWell well(Eigen::Vector3d(0.0, 0.0, 0.3));  // on the saddle
    NewtonOptions n;
    n.gradient_tolerance = 1e-12;
    if (side != 0.0) n.escape.bias = Eigen::Vector3d(side, 0.0, 0.0);
    const NewtonResult r = solve_newton(well, n);
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    REQUIRE(r.saddles_escaped.size() == 1);
    CHECK(r.saddles_escaped[0].energy == doctest::Approx(1.0));
    CHECK(r.saddles_escaped[0].lowest_eigenvalue == doctest::Approx(-4.0).epsilon(1e-9));
    // Without a bias: the side of the mode's positive largest entry.
    CHECK(well.get()[0] == doctest::Approx(side < 0.0 ? -1.0 : 1.0).epsilon(1e-9));
    CHECK(well.get()[2] == 0.3);  // the mechanism's coordinate never moved
    CHECK(r.energy < 1e-20);
    // At the minimum only the zero mode remains: not stable, not a saddle.
    CHECK_FALSE(r.stable);
    ++checked;
  }
  CHECK(checked == 3);
}

TEST_CASE("The branch bias measures the vertices' mean displacement along the direction") {
  LinkageProblem problem = flat_mechanism(3);  // 9 joints, the centre one held
  const Eigen::VectorXd bias = branch_bias(problem, Eigen::Vector3d(0.0, 0.0, 2.0));
  const Eigen::VectorXd q0 = problem.free_dofs();
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(q0.size());
  const RodLinkage& linkage = problem.linkage();
  const std::vector<int>& free = problem.free_indices();
  int moved = 0;
  for (size_t i = 0; i < free.size(); ++i)
    for (int j = 0; j < linkage.num_joints(); ++j)
      if (free[i] == linkage.joint_dof_offset(j) + 2) dq[i] = 1e-3 * (j + 1), ++moved;
  REQUIRE(moved == 8);
  const auto before = problem.vertex_positions();
  problem.set_free_dofs(q0 + dq);
  const auto after = problem.vertex_positions();
  double mean = 0.0;
  for (size_t v = 0; v < after.size(); ++v) mean += (after[v] - before[v]).z() / after.size();
  CHECK(mean > 0.0);
  CHECK(bias.dot(dq) == doctest::Approx(mean).epsilon(1e-12));
  const Eigen::VectorXd phi = -dq;
  CHECK(signed_direction(phi, bias).dot(dq) > 0.0);  // flipped onto the bias's side
  CHECK(signed_direction(phi, Eigen::VectorXd()).maxCoeff() == doctest::Approx(1.0));
}

}  // namespace xshell::test
