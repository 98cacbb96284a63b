#include "integrators/deployment/deployment.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/deployment_fixtures.hpp"

namespace xshell::test {

namespace {

DeploymentOptions tight(DeploymentSolver solver, double tolerance = 1e-10) {
  DeploymentOptions o;
  o.solver = solver;
  o.newton.gradient_tolerance = tolerance;
  o.newton.max_iterations = 100;
  o.dynamics.stopping.gradient_tolerance = tolerance;
  // The overdamped flow: each step starts near the next equilibrium, and the
  // second-order form would spend thousands of steps on the stiff
  // stretching modes' oscillations.
  o.dynamics.form = DynamicsForm::FirstOrder;
  o.dynamics.stopping.max_steps = 20000;
  return o;
}

DeploymentPlan average_plan(double angle, int steps) {
  DeploymentPlan p;
  p.average_angle = angle;
  p.steps = steps;
  return p;
}

// Every vertex's position, stacked (the unknowns' thetas and omegas depend
// on where the solvers rebased; the vertices do not).
Eigen::VectorXd stacked_vertices(const LinkageProblem& problem) {
  Eigen::VectorXd vertices(3 * problem.linkage().graph().vertices.size());
  for (int v = 0; v < vertices.size() / 3; ++v)
    vertices.segment<3>(3 * v) = problem.linkage().vertex_position(v);
  return vertices;
}

DeploymentResult run(LinkageProblem& problem, const DeploymentPlan& plan,
                     const DeploymentOptions& options) {
  const DeploymentResult r = deploy(problem, plan, options);
  CAPTURE(r.reason);
  REQUIRE(r.converged());
  return r;
}

}  // namespace

TEST_CASE(
    "Deployment by the average angle: every step converged on the constraint, torque positive") {
  LinkageProblem problem = dome_problem(3);
  const double start = average_opening_angle(problem.linkage());
  const DeploymentResult r =
      run(problem, average_plan(start + 0.4, 8), tight(DeploymentSolver::Newton));
  CHECK(r.steps.size() == 9);  // step 0 and 8 steps
  int rows = 0;
  for (const DeploymentStep& s : r.steps) {
    CAPTURE(s.step);
    CHECK(s.step == rows);
    CHECK(s.average_angle == doctest::Approx(start + 0.4 * s.fraction).epsilon(1e-12));
    CHECK(s.gradient_measure <= 1e-10);
    if (s.step > 0) {
      CHECK(s.torque > 0.0);  // the dome resists opening
      CHECK(s.stable);
      CHECK(s.iterations <= 8);  // a few Newton iterations per step
    }
    ++rows;
  }
  CHECK(rows == 9);
  CHECK(r.steps[0].energy.total() == doctest::Approx(0.0));  // stress-free as drawn
  CHECK(r.steps.back().energy.total() > 0.0);
  CHECK(average_opening_angle(problem.linkage()) == doctest::Approx(start + 0.4).epsilon(1e-12));
}

TEST_CASE(
    "Chord corrections: the same deployment with fewer Newton iterations and factorizations") {
  // The dome opened by 0.4 rad in 8 steps, at the default tolerance, with
  // and without chord corrections (constrained Newton, Schur complement).
  DeploymentOptions options = tight(DeploymentSolver::Newton, 1e-6);
  options.newton.max_chord_corrections = 0;
  LinkageProblem newton = dome_problem(3);
  const double start = average_opening_angle(newton.linkage());
  const DeploymentResult without = run(newton, average_plan(start + 0.4, 8), options);
  CHECK(without.chord_corrections == 0);
  options.newton.max_chord_corrections = 3;
  LinkageProblem chord = dome_problem(3);
  const DeploymentResult with = run(chord, average_plan(start + 0.4, 8), options);
  MESSAGE("dome: " << without.iterations << " iterations, " << without.factorizations
                   << " factorizations; with chords " << with.iterations << ", "
                   << with.factorizations << " and " << with.chord_corrections << " corrections");
  CHECK(with.chord_corrections >= 1);
  CHECK(with.iterations < without.iterations);
  CHECK(with.factorizations < without.factorizations);
  REQUIRE(with.steps.size() == without.steps.size());
  for (size_t i = 0; i < with.steps.size(); ++i) {
    CAPTURE(i);
    CHECK(with.steps[i].gradient_measure <= 1e-6);
    CHECK(with.steps[i].average_angle == doctest::Approx(without.steps[i].average_angle));
    CHECK(with.steps[i].torque == doctest::Approx(without.steps[i].torque).epsilon(1e-6));
  }
  // Both at the dome's equilibrium to the tolerance's accuracy.
  CHECK((stacked_vertices(chord) - stacked_vertices(newton)).lpNorm<Eigen::Infinity>() <
        1e-6 * chord.length_scale());
}

TEST_CASE(
    "The torque is the derivative of the equilibrium energy along the path (central differences)") {
  int compared = 0;
  for (DeploymentSolver solver : {DeploymentSolver::Newton, DeploymentSolver::Dynamics}) {
    CAPTURE(solver == DeploymentSolver::Newton);
    LinkageProblem problem = dome_problem(3);
    const double start = average_opening_angle(problem.linkage());
    const DeploymentOptions options = tight(solver, 1e-9);
    for (double opening : {0.25, 0.5}) {
      const DeploymentResult r = run(problem, average_plan(start + opening, 4), options);
      const double angle = r.steps.back().average_angle, torque = r.steps.back().torque;
      const double h = 1e-3;
      LinkageProblem plus = problem, minus = problem;
      const double e_plus =
          run(plus, average_plan(angle + h, 1), options).steps.back().energy.total();
      const double e_minus =
          run(minus, average_plan(angle - h, 1), options).steps.back().energy.total();
      const double derivative = (e_plus - e_minus) / (2.0 * h);
      CAPTURE(opening);
      CAPTURE(torque);
      CAPTURE(derivative);
      CHECK(torque > 0.0);
      CHECK(std::abs(torque - derivative) <= 1e-5 * std::abs(torque));
      ++compared;
    }
  }
  CHECK(compared == 4);
}

TEST_CASE("Prescribed angles: the joints reach their targets and the torque is dE/dtheta") {
  // Actuate the centre joint and one corner; the others follow.
  const int n = 3;
  StaticsSetup setup;
  setup.supports = {{4, {SupportDof::Position, SupportDof::Orientation, SupportDof::OpeningAngle}},
                    {0, {SupportDof::OpeningAngle}}};
  const LinkageProblem start(RodLinkage(dome_grid(n, 0.8), lath_material(RestShape::Input)), setup);
  const int centre = start.linkage().topology().joint_of_vertex[4],
            corner = start.linkage().topology().joint_of_vertex[0];
  const double a0 = start.linkage().joint(centre).opening_angle(),
               c0 = start.linkage().joint(corner).opening_angle();
  auto plan = [&](double delta) {
    DeploymentPlan p;
    p.joint_angles = {{centre, a0 + delta}, {corner, c0 + 0.5 * delta}};
    p.steps = 3;
    return p;
  };
  const DeploymentOptions options = tight(DeploymentSolver::Newton, 1e-9);
  LinkageProblem problem = start;
  const DeploymentResult r = run(problem, plan(0.3), options);
  CHECK(r.steps.size() == 4);
  CHECK(problem.linkage().joint(centre).opening_angle() ==
        doctest::Approx(a0 + 0.3).epsilon(1e-14));
  CHECK(problem.linkage().joint(corner).opening_angle() ==
        doctest::Approx(c0 + 0.15).epsilon(1e-14));
  // theta, the mean of the prescribed angles, moves by 0.225 over the path;
  // compare the torque with the equilibrium energies at delta 0.3 +/- h.
  const double h = 1e-3, dtheta = 0.75 * h;
  LinkageProblem plus = start, minus = start;
  const double e_plus = run(plus, plan(0.3 + h), options).steps.back().energy.total();
  const double e_minus = run(minus, plan(0.3 - h), options).steps.back().energy.total();
  const double derivative = (e_plus - e_minus) / (2.0 * dtheta);
  const double torque = r.steps.back().torque;
  CAPTURE(torque);
  CAPTURE(derivative);
  CHECK(std::abs(torque) > 0.0);
  CHECK(std::abs(torque - derivative) <= 1e-5 * std::abs(torque));
}

TEST_CASE(
    "A symmetric linkage deploys symmetrically, and closing it back returns the start energy") {
  const int n = 5;
  LinkageProblem problem = dome_problem(n, 0.6);
  const double start = average_opening_angle(problem.linkage());
  const auto start_angles = problem.opening_angles();
  const DeploymentOptions options = tight(DeploymentSolver::Newton, 1e-9);
  const DeploymentResult open = run(problem, average_plan(start + 0.45, 6), options);
  const double diagonal = problem.length_scale();
  const auto x = problem.vertex_positions();
  const auto alpha = problem.opening_angles();
  int pairs = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      // The mirror x <-> y maps vertex (i, j) to (j, i).
      const Eigen::Vector3d a = x[i * n + j], b = x[j * n + i];
      CHECK((Eigen::Vector3d(b.y(), b.x(), b.z()) - a).norm() < 1e-8 * diagonal);
      CHECK(std::abs(*alpha[i * n + j] - *alpha[j * n + i]) < 1e-8);
      ++pairs;
    }
  CHECK(pairs == n * n);
  // It really moved: the corners came closer along one diagonal.
  CHECK((x[0] - x[n * n - 1]).norm() < 0.95 * (problem.linkage().graph().vertices[0] -
                                               problem.linkage().graph().vertices[n * n - 1])
                                                  .norm());
  const double e_start = open.steps.front().energy.total(),
               e_open = open.steps.back().energy.total();
  CHECK(e_open > 0.0);
  const DeploymentResult close = run(problem, average_plan(start, 6), options);
  CHECK(close.steps.back().average_angle == doctest::Approx(start).epsilon(1e-13));
  CHECK(std::abs(close.steps.back().energy.total() - e_start) <= 1e-9 * e_open);
  // Back to the start: every joint at its input angle.
  const auto end_angles = problem.opening_angles();
  int joints = 0;
  for (size_t v = 0; v < end_angles.size(); ++v) {
    CHECK(std::abs(*end_angles[v] - *start_angles[v]) < 1e-7);
    ++joints;
  }
  CHECK(joints == n * n);
}

TEST_CASE("Newton and damped dynamics deploy to the same state") {
  LinkageProblem by_newton = dome_problem(3), by_dynamics = dome_problem(3);
  const double start = average_opening_angle(by_newton.linkage());
  const DeploymentPlan plan = average_plan(start + 0.35, 4);
  const DeploymentResult rn = run(by_newton, plan, tight(DeploymentSolver::Newton, 1e-8));
  const DeploymentResult rd = run(by_dynamics, plan, tight(DeploymentSolver::Dynamics, 1e-8));
  const double diagonal = by_newton.length_scale();
  const auto xn = by_newton.vertex_positions(), xd = by_dynamics.vertex_positions();
  const auto an = by_newton.opening_angles(), ad = by_dynamics.opening_angles();
  int vertices = 0, angles = 0;
  for (size_t v = 0; v < xn.size(); ++v) {
    CHECK((xn[v] - xd[v]).norm() <= 1e-6 * diagonal);
    ++vertices;
    if (an[v]) {
      CHECK(std::abs(*an[v] - *ad[v]) <= 1e-6);
      ++angles;
    }
  }
  CHECK(vertices == 9);
  CHECK(angles == 9);
  const double en = rn.steps.back().energy.total(), ed = rd.steps.back().energy.total();
  CHECK(std::abs(en - ed) <= 1e-7 * std::abs(en));
  CHECK(rn.steps.back().torque == doctest::Approx(rd.steps.back().torque).epsilon(1e-5));
  CHECK(rd.steps.back().stable);
}

TEST_CASE(
    "A flat grid of straight rods is a mechanism: it deploys without energy through the null-space "
    "step") {
  LinkageProblem problem = flat_mechanism(3);
  const double start = average_opening_angle(problem.linkage());
  const DeploymentResult r =
      run(problem, average_plan(start + 0.5, 5), tight(DeploymentSolver::Newton));
  int steps = 0;
  for (const DeploymentStep& s : r.steps) {
    CHECK(std::abs(s.energy.total()) < 1e-12);
    CHECK(std::abs(s.torque) < 1e-9);
    CHECK(s.stable);  // on the constraint, the mechanism mode is gone
    ++steps;
  }
  CHECK(steps == 6);
  // A rhombic grid: every joint at the average.
  for (int j = 0; j < problem.linkage().num_joints(); ++j)
    CHECK(problem.linkage().joint(j).opening_angle() == doctest::Approx(start + 0.5).epsilon(1e-8));
}

TEST_CASE("A failing step is halved and retried, the deployment reports a step it cannot take") {
  LinkageProblem problem = dome_problem(3);
  const double start = average_opening_angle(problem.linkage());
  DeploymentOptions options = tight(DeploymentSolver::Newton);
  // Too few for a whole step of 0.4 rad (5 Newton iterations without chord
  // corrections), enough for smaller ones.
  options.newton.max_iterations = 4;
  options.newton.max_chord_corrections = 0;
  const DeploymentResult r = deploy(problem, average_plan(start + 0.4, 1), options);
  CAPTURE(r.reason);
  REQUIRE(r.converged());
  CHECK(r.failed_attempts >= 1);
  CHECK(r.steps.size() >= 3);
  CHECK(r.steps.back().fraction == 1.0);
  int halved = 0;
  for (const DeploymentStep& s : r.steps) halved += s.halvings;
  CHECK(halved == r.failed_attempts);

  LinkageProblem again = dome_problem(3);
  options.newton.max_iterations = 1;
  options.max_halvings = 2;
  const DeploymentResult failed = deploy(again, average_plan(start + 0.4, 1), options);
  CHECK(failed.status == SolveStatus::StepFailed);
  CHECK(failed.failed_attempts == 3);
  CHECK(failed.steps.size() == 1);  // only the start
  // Left at the last accepted state, the start.
  CHECK(average_opening_angle(again.linkage()) == doctest::Approx(start).epsilon(1e-14));
}

TEST_CASE(
    "A first attempt beyond the step's iteration budget is halved, its retries are not bound") {
  const double start = average_opening_angle(dome_problem(3).linkage());
  LinkageProblem free = dome_problem(3);
  const DeploymentOptions unbounded = tight(DeploymentSolver::Newton);
  const DeploymentResult reference = deploy(free, average_plan(start + 0.4, 1), unbounded);
  REQUIRE(reference.converged());
  REQUIRE(reference.steps.size() == 2);
  REQUIRE(reference.steps[1].iterations > 2);  // more than the budget below

  LinkageProblem problem = dome_problem(3);
  DeploymentOptions options = unbounded;
  options.step_iterations = 2;
  const DeploymentResult r = deploy(problem, average_plan(start + 0.4, 1), options);
  CAPTURE(r.reason);
  REQUIRE(r.converged());
  // Every step's first attempt had 2 iterations; a step that needed more
  // was accepted at its first retry, which had as many as it needed.
  REQUIRE(r.steps.size() >= 3);
  CHECK(r.steps[1].halvings == 1);
  int retried = 0;
  for (size_t k = 1; k < r.steps.size(); ++k) {
    CAPTURE(k);
    CHECK(r.steps[k].halvings <= 1);
    if (r.steps[k].halvings == 0) CHECK(r.steps[k].iterations <= 2);
    retried += r.steps[k].halvings;
  }
  CHECK(r.failed_attempts == retried);
  CHECK(r.steps.back().fraction == 1.0);
  // The same end state.
  for (int v = 0; v < static_cast<int>(problem.linkage().graph().vertices.size()); ++v)
    CHECK((problem.linkage().vertex_position(v) - free.linkage().vertex_position(v)).norm() <=
          1e-8);
  // With no halving allowed there is no budget.
  LinkageProblem again = dome_problem(3);
  options.max_halvings = 0;
  const DeploymentResult single = deploy(again, average_plan(start + 0.4, 1), options);
  CHECK(single.converged());
  CHECK(single.failed_attempts == 0);
}

}  // namespace xshell::test

namespace xshell::test {

TEST_CASE("Each predictor lands on the same path and the curved one needs the fewest iterations") {
  std::vector<long> iterations;
  std::vector<Eigen::VectorXd> ends;
  for (DeploymentPredictor predictor :
       {DeploymentPredictor::UniformShift, DeploymentPredictor::Tangent,
        DeploymentPredictor::Quadratic}) {
    LinkageProblem problem = dome_problem(5);
    const double start = average_opening_angle(problem.linkage());
    DeploymentOptions options = tight(DeploymentSolver::Newton, 1e-9);
    options.predictor = predictor;
    const DeploymentResult r = deploy(problem, average_plan(start + 0.6, 12), options);
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    // On this smooth path the curved prediction always starts lower.
    CHECK(r.curvature_dropped == 0);
    long steps_iterations = 0;  // of the steps after the first two (step 0 has no predictor)
    for (size_t k = 2; k < r.steps.size(); ++k) steps_iterations += r.steps[k].iterations;
    // One factorization per iteration, and the final state's, which serves
    // both the stability test and the next step's tangent.
    if (predictor != DeploymentPredictor::UniformShift)
      for (size_t k = 1; k < r.steps.size(); ++k) {
        CAPTURE(k);
        CHECK(r.steps[k].factorizations == r.steps[k].iterations + 1);
      }
    iterations.push_back(steps_iterations);
    ends.push_back(stacked_vertices(problem));
  }
  MESSAGE("Newton iterations of steps 2-12: uniform shift "
          << iterations[0] << ", tangent " << iterations[1] << ", curved " << iterations[2]);
  CHECK(iterations[1] < iterations[0]);
  CHECK(iterations[2] < iterations[1]);
  // The same equilibria: the vertices (the unknowns' thetas and omegas
  // depend on where the solvers rebased).
  for (const Eigen::VectorXd& end : ends) CHECK((end - ends[0]).cwiseAbs().maxCoeff() <= 1e-9);
}

}  // namespace xshell::test

namespace xshell::test {

TEST_CASE("Adaptive increments reach the same end in fewer steps, the torque on the same curve") {
  LinkageProblem equal = dome_problem(5);
  const double start = average_opening_angle(equal.linkage());
  const DeploymentOptions options = tight(DeploymentSolver::Newton, 1e-9);
  const DeploymentResult fixed = run(equal, average_plan(start + 0.6, 48), options);
  LinkageProblem adaptive = dome_problem(5);
  DeploymentPlan plan = average_plan(start + 0.6, 48);
  plan.largest_step = 0.2;
  const DeploymentResult grown = run(adaptive, plan, options);
  MESSAGE("steps: equal " << fixed.steps.size() - 1 << ", adaptive " << grown.steps.size() - 1
                          << "; iterations " << fixed.iterations << ", " << grown.iterations);
  CHECK(grown.steps.size() < fixed.steps.size());
  CHECK(grown.steps.back().average_angle == doctest::Approx(start + 0.6).epsilon(1e-9));
  double largest = 0.0;
  for (size_t k = 1; k < grown.steps.size(); ++k)
    largest = std::max(largest, grown.steps[k].average_angle - grown.steps[k - 1].average_angle);
  CHECK(largest <= 0.2 + 1e-9);
  CHECK(largest > 0.6 / 48 * 1.5);  // it grew
  for (int v = 0; v < static_cast<int>(equal.linkage().graph().vertices.size()); ++v)
    CHECK((equal.linkage().vertex_position(v) - adaptive.linkage().vertex_position(v)).norm() <=
          1e-8);
  // Each adaptive step's torque lies on the equal steps' torque curve
  // (linear interpolation between its neighbours there, the curve's
  // second difference bounding the error).
  for (size_t k = 1; k + 1 < grown.steps.size(); ++k) {
    const DeploymentStep& g = grown.steps[k];
    size_t j = 1;
    while (j + 1 < fixed.steps.size() && fixed.steps[j].average_angle < g.average_angle) ++j;
    const DeploymentStep &a = fixed.steps[j - 1], &b = fixed.steps[j];
    const double w = (g.average_angle - a.average_angle) / (b.average_angle - a.average_angle);
    CAPTURE(k);
    CHECK(g.torque == doctest::Approx((1 - w) * a.torque + w * b.torque).epsilon(1e-3));
  }
}

}  // namespace xshell::test

namespace xshell::test {

TEST_CASE("Newton steps along the linkage's curve and along the line reach the same equilibria") {
  std::vector<long> iterations;
  std::vector<double> first_energies;  // after the first Newton iteration
  std::vector<Eigen::VectorXd> ends;
  for (const bool curve : {false, true}) {
    LinkageProblem problem = dome_problem(5);
    const double start = average_opening_angle(problem.linkage());
    DeploymentOptions options = tight(DeploymentSolver::Newton, 1e-9);
    options.newton.follow_path = curve;
    DeploymentCallbacks callbacks;
    double first_energy = 0.0;
    callbacks.on_newton_iteration = [&](const NewtonReport& report) {
      if (report.iteration == 1 && first_energy == 0.0) first_energy = report.energy;
    };
    // One long step: the rods turn by 0.8 rad.
    const DeploymentResult r = deploy(problem, average_plan(start + 0.8, 1), options, callbacks);
    CAPTURE(r.reason);
    REQUIRE(r.converged());
    iterations.push_back(r.iterations);
    first_energies.push_back(first_energy);
    ends.push_back(stacked_vertices(problem));
  }
  MESSAGE("Newton iterations: along the line " << iterations[0] << ", along the curve "
                                               << iterations[1]);
  // The curve moves the first iterate elsewhere (the option is followed),
  // and takes no more iterations (one fewer in a release build, as many
  // under the sanitizers' build).
  CHECK(first_energies[0] != 0.0);
  CHECK(first_energies[1] != first_energies[0]);
  CHECK(iterations[1] <= iterations[0]);
  CHECK((ends[1] - ends[0]).cwiseAbs().maxCoeff() <= 1e-9);
}

}  // namespace xshell::test
