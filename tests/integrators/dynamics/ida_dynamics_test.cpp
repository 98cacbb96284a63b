#include "integrators/dynamics/ida_dynamics.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/dynamics/ida_system.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"
#include "integrators/newton/newton.hpp"
#include "integrators/toy_objectives.hpp"

namespace xshell::test {

namespace {

struct DynamicsRun {
  DynamicsResult result;
  std::vector<DynamicsReport> reports;

  // Largest rise of E + kinetic energy between consecutive steps.
  double max_total_energy_rise() const {
    double rise = 0.0;
    for (size_t k = 1; k < reports.size(); ++k) {
      const double before = reports[k - 1].energy + reports[k - 1].kinetic_energy;
      const double after = reports[k].energy + reports[k].kinetic_energy;
      rise = std::max(rise, after - before);
    }
    return rise;
  }
};

DynamicsRun run_dynamics(Objective& objective, const DynamicsOptions& options,
                         const std::atomic<bool>* stop = nullptr) {
  DynamicsRun run;
  DynamicsCallbacks callbacks;
  callbacks.stop = stop;
  callbacks.on_step = [&](const DynamicsReport& r) { run.reports.push_back(r); };
  run.result = solve_dynamics(objective, options, callbacks);
  return run;
}

DynamicsOptions tight(DynamicsForm form, MassModel mass) {
  DynamicsOptions options;
  options.form = form;
  options.mass = mass;
  options.stopping.gradient_tolerance = 1e-10;
  return options;
}

// Newton to the toys' equilibria, as tight as tight() asks of the dynamics.
NewtonOptions reference_newton() {
  NewtonOptions newton;
  newton.gradient_tolerance = 1e-10;
  newton.max_iterations = 500;
  return newton;
}

std::string label(const DynamicsOptions& o) {
  return std::string(o.form == DynamicsForm::SecondOrder ? "second order" : "first order") + ", " +
         (o.mass == MassModel::Physical ? "physical mass" : "fictitious mass");
}

struct Toy {
  std::string name;
  std::function<Eigen::VectorXd(const std::function<void(Objective&)>&)>
      run;  // returns configuration
};

// Solves a fresh copy of a toy with `solve` and returns its final configuration.
template <class Make>
Eigen::VectorXd solve_fresh(Make make, const std::function<void(Objective&)>& solve) {
  StencilObjective objective = make();
  solve(objective);
  return objective.configuration();
}

std::vector<Toy> toys() {
  std::vector<Toy> list;
  list.push_back(
      {"chain", [](const auto& solve) { return solve_fresh([] { return make_chain(); }, solve); }});
  list.push_back({"rosenbrock", [](const auto& solve) {
                    return solve_fresh([] { return make_rosenbrock(8); }, solve);
                  }});
  list.push_back({"buckled column", [](const auto& solve) {
                    ColumnOptions o;
                    o.imperfection = 0.05;
                    return solve_fresh([o] { return make_column(o); }, solve);
                  }});
  list.push_back({"offset chain", [](const auto& solve) {
                    StencilObjective inner = make_chain();
                    OffsetObjective offset(inner, 0.3);
                    solve(offset);
                    return offset.configuration();
                  }});
  return list;
}

}  // namespace

TEST_CASE("damped dynamics reaches Newton's equilibria, with energy decreasing") {
  const NewtonOptions newton = reference_newton();
  int compared = 0;
  for (const Toy& toy : toys()) {
    const Eigen::VectorXd reference = toy.run([&](Objective& o) {
      const NewtonResult r = solve_newton(o, newton);
      REQUIRE(r.converged());
      REQUIRE(r.stable);
    });
    for (DynamicsForm form : {DynamicsForm::SecondOrder, DynamicsForm::FirstOrder})
      for (MassModel mass : {MassModel::Physical, MassModel::Fictitious}) {
        const DynamicsOptions options = tight(form, mass);
        DynamicsRun run;
        const Eigen::VectorXd q = toy.run([&](Objective& o) { run = run_dynamics(o, options); });
        const double distance = (q - reference).norm() / reference.norm();
        const double drop = run.reports.front().energy - run.result.energy;
        const double rise = run.max_total_energy_rise();
        INFO(toy.name << ", " << label(options) << ": " << run.result.reason);
        REQUIRE(run.result.status == SolveStatus::Converged);
        CHECK(run.result.gradient_measure <= 1e-10);
        CHECK(run.result.stable);
        CHECK(distance < 1e-6);
        CHECK(drop > 0.0);
        CHECK(rise <= 1e-6 * drop);  // E + K never increases beyond round-off/truncation
        CHECK(run.result.iterations == static_cast<long>(run.reports.size()) - 1);
        // Steps grow as the motion dies out.
        CHECK(run.reports.back().step_size > 100.0 * run.reports[1].step_size);
        ++compared;
        MESSAGE(toy.name << ", " << label(options) << ": " << run.result.iterations << " steps, "
                         << run.result.rebases << " rebases, " << run.result.factorizations
                         << " factorizations, c = " << run.result.damping << ", t = "
                         << run.result.time << ", last h = " << run.reports.back().step_size
                         << ", |dq|/|q| = " << distance << ", max rise of E+K = " << rise
                         << " (drop " << drop << "), " << run.result.seconds << " s");
      }
  }
  CHECK(compared == 16);
}

TEST_CASE("damped dynamics near the column's saddle") {
  NewtonOptions newton;
  newton.gradient_tolerance = 1e-10;
  ColumnOptions far;
  far.imperfection = 0.05;
  StencilObjective reference = make_column(far);
  REQUIRE(solve_newton(reference, newton).converged());
  const int middle = column_middle_y(far);

  SUBCASE("a tiny imperfection grows into the buckled minimum") {
    for (DynamicsForm form : {DynamicsForm::SecondOrder, DynamicsForm::FirstOrder}) {
      ColumnOptions near = far;
      near.imperfection = 1e-4;
      StencilObjective column = make_column(near);
      const DynamicsRun run = run_dynamics(column, tight(form, MassModel::Physical));
      INFO(label(tight(form, MassModel::Physical)) << ": " << run.result.reason);
      REQUIRE(run.result.status == SolveStatus::Converged);
      CHECK(run.result.stable);
      CHECK(column.get()[middle] > 0.05);  // buckled towards the imperfection
      CHECK((column.get() - reference.get()).norm() < 1e-6 * reference.get().norm());
      // Within the integrator's tolerance: IDA's local error control (rtol
      // 1e-3) bounds each step's energy error; the rises seen while the
      // column buckles are 1e-6 of the drop (first order, Rayleigh damping).
      CHECK(run.max_total_energy_rise() <= 1e-5 * (run.reports.front().energy - run.result.energy));
      MESSAGE("column from imperfection 1e-4, "
              << label(tight(form, MassModel::Physical)) << ": " << run.result.iterations
              << " steps (" << run.result.rejected_steps
              << " rejected: E + K rose), t = " << run.result.time);
    }
  }
  SUBCASE("on the saddle, steps are held below a failed factorization") {
    // Exactly straight, the column stays on its saddle, where K is positive
    // definite only for short steps: without the cap IDA grows its step
    // into the same failed factorization again and again.
    for (DynamicsForm form : {DynamicsForm::SecondOrder, DynamicsForm::FirstOrder}) {
      DynamicsResult runs[2];
      Eigen::VectorXd ends[2];
      for (bool cap : {false, true}) {
        StencilObjective column = make_column({});
        DynamicsOptions o = tight(form, MassModel::Physical);
        o.steps.cap_indefinite = cap;
        o.escape.enabled = false;  // the saddle itself is studied
        runs[cap] = run_dynamics(column, o).result;
        ends[cap] = column.get();
        INFO(label(o) << ", cap " << cap << ": " << runs[cap].reason);
        REQUIRE(runs[cap].status == SolveStatus::Converged);
        CHECK_FALSE(runs[cap].stable);
      }
      MESSAGE("straight column on its saddle, "
              << label(tight(form, MassModel::Physical))
              << ": steps, factorizations (convergence failures) " << runs[0].iterations << ", "
              << runs[0].factorizations << " (" << runs[0].convergence_failures
              << ") without the step cap, " << runs[1].iterations << ", " << runs[1].factorizations
              << " (" << runs[1].convergence_failures << ") with it");
      CHECK((ends[1] - ends[0]).norm() <= 1e-6 * ends[0].norm());
      CHECK(runs[1].convergence_failures < runs[0].convergence_failures);
      CHECK(runs[1].factorizations < runs[0].factorizations);
    }
  }
  SUBCASE("checking the Hessian for the end game on the saddle leaves IDA's factorization alone") {
    // With an early end game, the Hessian is checked (and found indefinite)
    // while IDA is still integrating with its own factorization of K.
    for (DynamicsForm form : {DynamicsForm::SecondOrder, DynamicsForm::FirstOrder}) {
      StencilObjective column = make_column({});
      DynamicsOptions o = tight(form, MassModel::Physical);
      o.endgame.step_length = 1.0;
      o.escape.enabled = false;
      const DynamicsRun run = run_dynamics(column, o);
      INFO(label(o) << ": " << run.result.reason);
      REQUIRE(run.result.status == SolveStatus::Converged);
      CHECK_FALSE(run.result.stable);
      CHECK(column.get()[middle] == 0.0);
    }
  }
  SUBCASE("a converged end game's stability test is the run's, on the saddle and off it") {
    // The run reports the stability the end game's Newton found at the
    // final state (one factorization less); a fresh factorization there
    // must agree. The straight column stays on its saddle, the imperfect
    // one buckles into the minimum.
    for (double imperfection : {0.0, 1e-4}) {
      ColumnOptions c;
      c.imperfection = imperfection;
      StencilObjective column = make_column(c);
      DynamicsOptions o = tight(DynamicsForm::SecondOrder, MassModel::Physical);
      o.escape.enabled = false;
      const DynamicsRun run = run_dynamics(column, o);
      INFO("imperfection " << imperfection << ": " << run.result.reason);
      REQUIRE(run.result.status == SolveStatus::Converged);
      REQUIRE(run.result.endgame_steps >= 1);
      CholeskySolver fresh;
      CHECK(run.result.stable == is_positive_definite(fresh, column.hessian()));
      CHECK(run.result.stable == (imperfection > 0.0));
    }
  }
  SUBCASE("an exactly straight start stays on the saddle, reported unstable") {
    StencilObjective column = make_column({});
    DynamicsOptions o = tight(DynamicsForm::FirstOrder, MassModel::Physical);
    o.escape.enabled = false;
    const DynamicsRun run = run_dynamics(column, o);
    INFO(run.result.reason);
    REQUIRE(run.result.status == SolveStatus::Converged);
    CHECK(column.get()[middle] == 0.0);
    CHECK_FALSE(run.result.stable);
  }
}

// A chain in tension: its Hessian is positive definite from the start.
StencilObjective make_taut_chain() {
  ChainOptions o;
  o.span_ratio = 1.05;
  return make_chain(o);
}

TEST_CASE(
    "a run settled at a saddle within endgame_gradient_factor of the tolerance ends with the end "
    "game") {
  // The exactly straight column beyond Euler's load stays on its saddle
  // (see above). Its Hessian is indefinite there, so the end game by step
  // length never starts, and K is positive definite only for short steps:
  // the gradient falls by a constant factor per capped step. Newton, from
  // the same start, stops on the same saddle.
  NewtonOptions newton;
  newton.gradient_tolerance = 1e-10;
  newton.escape.enabled = false;  // the saddle itself is studied
  StencilObjective reference = make_column({});
  const NewtonResult saddle = solve_newton(reference, newton);
  REQUIRE(saddle.converged());
  REQUIRE_FALSE(saddle.stable);
  for (DynamicsForm form : {DynamicsForm::SecondOrder, DynamicsForm::FirstOrder}) {
    DynamicsOptions o = tight(form, MassModel::Physical);
    o.escape.enabled = false;
    std::vector<DynamicsRun> runs;
    for (double factor : {0.0, 100.0}) {
      o.endgame.gradient_factor = factor;
      StencilObjective column = make_column({});
      runs.push_back(run_dynamics(column, o));
      const DynamicsRun& run = runs.back();
      INFO(label(o) << ", factor " << factor << ": " << run.result.reason);
      REQUIRE(run.result.status == SolveStatus::Converged);
      CHECK(run.result.gradient_measure <= o.stopping.gradient_tolerance);
      CHECK_FALSE(run.result.stable);
      CHECK((column.configuration() - reference.configuration()).norm() <=
            1e-6 * reference.configuration().norm());
    }
    const DynamicsResult &plain = runs[0].result, &settled = runs[1].result;
    CHECK(plain.endgame_steps == 0);
    REQUIRE(settled.endgame_steps >= 1);
    // The dynamics handed over at rest, within 100 times the tolerance.
    const std::vector<DynamicsReport>& reports = runs[1].reports;
    const DynamicsReport& handover =
        reports[reports.size() - 1 - static_cast<size_t>(settled.endgame_steps)];
    CHECK(handover.order > 0);
    CHECK(handover.gradient_measure <= 100.0 * o.stopping.gradient_tolerance);
    CHECK(handover.gradient_measure > o.stopping.gradient_tolerance);
    CHECK(settled.iterations < plain.iterations);
    MESSAGE(label(o) << ": " << plain.iterations << " steps without the settled end game, "
                     << settled.iterations << " with it (" << settled.endgame_steps
                     << " of them Newton)");
  }
}

TEST_CASE("a run at rest in a stable basin hands over to the end game, whatever its gradient") {
  // The end game by step length is kept out of reach (step_length 1e12),
  // so that a hand-over at rest with a gradient above gradient_factor
  // times the tolerance can only come from EndgameOptions::rest_check_fall.
  const NewtonOptions newton = reference_newton();
  int handed_over = 0;
  for (const Toy& toy : toys()) {
    const Eigen::VectorXd reference =
        toy.run([&](Objective& o) { REQUIRE(solve_newton(o, newton).converged()); });
    DynamicsOptions o = tight(DynamicsForm::SecondOrder, MassModel::Physical);
    o.endgame.step_length = 1e12;
    std::vector<DynamicsRun> runs;
    for (double fall : {0.0, 0.1}) {
      o.endgame.rest_check_fall = fall;
      runs.emplace_back();
      const Eigen::VectorXd q =
          toy.run([&](Objective& obj) { runs.back() = run_dynamics(obj, o); });
      const DynamicsResult& r = runs.back().result;
      INFO(toy.name << ", fall " << fall << ": " << r.reason);
      REQUIRE(r.status == SolveStatus::Converged);
      CHECK(r.stable);
      CHECK((q - reference).norm() < 1e-6 * reference.norm());
    }
    const DynamicsResult &plain = runs[0].result, &rested = runs[1].result;
    if (rested.endgame_steps == 0) continue;
    const std::vector<DynamicsReport>& reports = runs[1].reports;
    const DynamicsReport& handover =
        reports[reports.size() - 1 - static_cast<size_t>(rested.endgame_steps)];
    if (!(handover.gradient_measure > o.endgame.gradient_factor * o.stopping.gradient_tolerance))
      continue;  // the older trigger's hand-over
    ++handed_over;
    INFO(toy.name);
    CHECK(handover.order > 0);
    const double scale =
        std::max(std::abs(reports.front().energy - handover.energy), std::abs(handover.energy));
    CHECK(handover.kinetic_energy <= o.stopping.kinetic_tolerance * scale);
    CHECK(rested.iterations < plain.iterations);
    MESSAGE(toy.name << ": " << plain.iterations << " steps without the end game at rest, "
                     << rested.iterations << " with it (" << rested.endgame_steps
                     << " of them Newton), handed over at gradient " << handover.gradient_measure);
  }
  CHECK(handed_over >= 1);
}

TEST_CASE("the overdamped velocity puts the second-order form on its slow manifold") {
  StencilObjective chain = make_taut_chain();
  ObjectiveEvaluator evaluator(chain);
  evaluator.sync();
  const Eigen::Index n = chain.size();
  REQUIRE(evaluator.gradient().norm() > 0.0);
  Damping damping;  // C = a M + b H, positive definite (H is at this start)
  damping.mass_coefficient = 0.5;
  damping.stiffness_coefficient = 0.2;
  damping.stiffness = chain.hessian();
  DynamicsSystem system(evaluator, DynamicsForm::SecondOrder, chain.mass(), damping);
  Eigen::VectorXd y(2 * n);
  y.head(n) = chain.get();
  y.tail(n) = system.overdamped_velocity(0.0);
  const Eigen::VectorXd yp = system.consistent_derivatives(y, 0.0);
  const double scale = evaluator.gradient().cwiseQuotient(chain.mass()).norm();
  CHECK((yp.head(n) - y.tail(n)).norm() == 0.0);  // q' = v
  CHECK(yp.tail(n).norm() <= 1e-10 * scale);      // v' = 0: no initial layer
  // With inertia 1/T the acceleration is v / T instead.
  y.tail(n) = system.overdamped_velocity(0.0, 2.0);
  const Eigen::VectorXd limited = system.consistent_derivatives(y, 0.0);
  CHECK((limited.tail(n) - 2.0 * y.tail(n)).norm() <= 1e-10 * scale);
  // From rest the whole force accelerates: v' = -M^-1 grad E.
  y.tail(n).setZero();
  const Eigen::VectorXd from_rest = system.consistent_derivatives(y, 0.0);
  CHECK((from_rest.tail(n) + evaluator.gradient().cwiseQuotient(chain.mass())).norm() <=
        1e-12 * scale);
}

TEST_CASE("damped dynamics from the slow manifold: moving at the start, same equilibrium") {
  NewtonOptions newton;
  newton.gradient_tolerance = 1e-10;
  StencilObjective reference = make_taut_chain();
  REQUIRE(solve_newton(reference, newton).converged());
  for (DynamicsStart start : {DynamicsStart::Rest, DynamicsStart::SlowManifold}) {
    StencilObjective chain = make_taut_chain();
    DynamicsOptions options = tight(DynamicsForm::SecondOrder, MassModel::Physical);
    options.start.velocity = start;
    const DynamicsRun run = run_dynamics(chain, options);
    INFO((start == DynamicsStart::Rest ? "rest" : "slow manifold") << ": " << run.result.reason);
    REQUIRE(run.result.status == SolveStatus::Converged);
    if (start == DynamicsStart::Rest)
      CHECK(run.reports.front().kinetic_energy == 0.0);
    else
      CHECK(run.reports.front().kinetic_energy > 0.0);
    CHECK((chain.get() - reference.get()).norm() < 1e-6 * reference.get().norm());
    const double drop =
        run.reports.front().energy + run.reports.front().kinetic_energy - run.result.energy;
    CHECK(drop > 0.0);
    CHECK(run.max_total_energy_rise() <= 1e-6 * drop);
  }
}

TEST_CASE("damped dynamics: stop flag, step limit and non-finite values") {
  SUBCASE("stop flag") {
    StencilObjective chain = make_chain();
    std::atomic<bool> stop{false};
    DynamicsRun run;
    DynamicsCallbacks callbacks;
    callbacks.stop = &stop;
    callbacks.on_step = [&](const DynamicsReport& r) {
      run.reports.push_back(r);
      if (r.step == 5) stop = true;
    };
    run.result =
        solve_dynamics(chain, tight(DynamicsForm::SecondOrder, MassModel::Physical), callbacks);
    CHECK(run.result.status == SolveStatus::Interrupted);
    CHECK(run.result.iterations == 5);
    CHECK(run.reports.size() == 6);
    CHECK(std::isfinite(chain.energy()));
  }
  SUBCASE("step limit") {
    StencilObjective chain = make_chain();
    DynamicsOptions options = tight(DynamicsForm::SecondOrder, MassModel::Physical);
    options.stopping.max_steps = 7;
    const DynamicsRun run = run_dynamics(chain, options);
    CHECK(run.result.status == SolveStatus::IterationLimit);
    CHECK(run.result.iterations == 7);
  }
  SUBCASE("NaN at the start") {
    SqrtWell well(Eigen::VectorXd::Constant(3, -1.0), InvalidBehaviour::NaN);
    const DynamicsRun run =
        run_dynamics(well, tight(DynamicsForm::SecondOrder, MassModel::Physical));
    CHECK(run.result.status == SolveStatus::NonFinite);
    CHECK(run.result.iterations == 0);
    CHECK_FALSE(run.result.stable);
  }
  SUBCASE("the motion runs into a NaN region: NonFinite, left at the last good step") {
    const Eigen::VectorXd start = Eigen::VectorXd::Constant(3, 4.0);
    SqrtWell well(start, InvalidBehaviour::NaN, 3.9);  // the minimum x = 1 is unreachable
    const DynamicsRun run =
        run_dynamics(well, tight(DynamicsForm::FirstOrder, MassModel::Physical));
    INFO(run.result.reason);
    CHECK(run.result.status == SolveStatus::NonFinite);
    CHECK(well.invalid_encounters() > 0);
    CHECK(std::isfinite(well.energy()));
    CHECK((well.get().array() >= 3.9).all());
    CHECK(run.result.iterations == static_cast<long>(run.reports.size()) - 1);
  }
  SUBCASE("the motion runs into invalid configurations: IntegratorFailed") {
    SqrtWell well(Eigen::VectorXd::Constant(3, 4.0), InvalidBehaviour::Throw, 3.9);
    const DynamicsRun run =
        run_dynamics(well, tight(DynamicsForm::SecondOrder, MassModel::Physical));
    INFO(run.result.reason);
    CHECK(run.result.status == SolveStatus::IntegratorFailed);
    CHECK(well.invalid_encounters() > 0);
    CHECK((well.get().array() >= 3.9).all());
  }
}

TEST_CASE("an unexpected exception inside an IDA callback reaches the caller") {
  StencilObjective chain = make_chain();
  FaultyObjective faulty(chain, 5);
  CHECK_THROWS_AS(solve_dynamics(faulty, tight(DynamicsForm::SecondOrder, MassModel::Physical)),
                  std::runtime_error);
  CHECK(faulty.calls() >= 5);
}

TEST_CASE("an accepted step that ends in an invalid configuration is taken again, shorter") {
  // IDA accepts the state of its last Newton correction without evaluating
  // it. A first run records the set() call that moves the objective to the
  // state of step 5; a second, identical run finds that state invalid.
  for (DynamicsForm form : {DynamicsForm::SecondOrder, DynamicsForm::FirstOrder}) {
    const DynamicsOptions options = tight(form, MassModel::Physical);
    CAPTURE(label(options));
    StencilObjective reference_chain = make_chain();
    InvalidAtCall reference(reference_chain, 0);
    std::vector<long> calls_at_step;
    std::vector<double> energies, step_sizes;
    DynamicsCallbacks callbacks;
    callbacks.on_step = [&](const DynamicsReport& r) {
      calls_at_step.push_back(reference.calls());
      energies.push_back(r.energy);
      step_sizes.push_back(r.step_size);
    };
    const DynamicsResult clean = solve_dynamics(reference, options, callbacks);
    REQUIRE(clean.converged());
    REQUIRE(calls_at_step.size() > 6);
    REQUIRE(calls_at_step[5] > calls_at_step[4]);  // step 5's state was moved to

    StencilObjective chain = make_chain();
    InvalidAtCall invalid(chain, calls_at_step[5]);
    const DynamicsRun run = run_dynamics(invalid, options);
    INFO(run.result.reason);
    CHECK(invalid.calls() >= calls_at_step[5]);
    REQUIRE(run.result.converged());
    // Step 5 was rejected and taken again with half its length. (Later
    // steps follow another path than the clean run's, which may reject
    // steps of its own.)
    CHECK(run.result.rejected_steps >= clean.rejected_steps + 1);
    REQUIRE(run.reports.size() > 5);
    CHECK(run.reports[5].step_size <= 0.5 * step_sizes[5] * (1.0 + 1e-12));
    CHECK(run.result.stable);
    CHECK((chain.configuration() - reference_chain.configuration()).norm() <=
          1e-8 * reference_chain.configuration().norm());
    // The steps before the invalid state are those of the clean run.
    for (size_t k = 0; k < 5; ++k) CHECK(run.reports[k].energy == energies[k]);
  }
}

TEST_CASE("damped dynamics stops on divergence, and below the round-off floor") {
  SUBCASE("a load that nothing holds: divergence, long before the step limit") {
    // Before: every step up to the limit (a force of 1e30 on a linkage:
    // past 120 s, the energy at -3.6e36). Windows of 50 steps: the toy's
    // motion otherwise reaches the end game (Newton), which stops on
    // stagnation instead.
    Slope slope(3, 2.0);
    DynamicsOptions options = tight(DynamicsForm::SecondOrder, MassModel::Physical);
    options.stopping.progress.window = 50;
    const DynamicsRun run = run_dynamics(slope, options);
    INFO(run.result.reason);
    CHECK(run.result.status == SolveStatus::Diverged);
    CHECK(run.result.reason.rfind("diverging: over the last 50 steps the energy fell faster", 0) ==
          0);
    CHECK(run.result.iterations < 1000);
    CHECK(std::isfinite(slope.energy()));
  }
  SUBCASE("a tolerance of 1e-30: a stop with a reason, long before the step limit") {
    StencilObjective chain = make_chain();
    DynamicsOptions options = tight(DynamicsForm::SecondOrder, MassModel::Physical);
    options.stopping.gradient_tolerance = 1e-30;
    const DynamicsRun run = run_dynamics(chain, options);
    INFO(run.result.reason);
    CHECK_FALSE(run.result.converged());
    CHECK(run.result.status != SolveStatus::IterationLimit);
    CHECK(run.result.iterations < 20000);
  }
}

}  // namespace xshell::test
