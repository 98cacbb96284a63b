#include "integrators/newton/newton.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <cstdio>
#include <vector>

#include "integrators/convergence.hpp"
#include "integrators/toy_objectives.hpp"

namespace xshell::test::newton_test {

namespace {

struct Recorded {
  NewtonResult result;
  std::vector<NewtonReport> reports;
  std::vector<double> measures() const {
    std::vector<double> m;
    for (const NewtonReport& r : reports) m.push_back(r.gradient_measure);
    return m;
  }
};

Recorded run_newton(Objective& objective, NewtonOptions options = {}) {
  Recorded run;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport& r) { run.reports.push_back(r); };
  run.result = solve_newton(objective, options, callbacks);
  return run;
}

NewtonOptions tight() {
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  return options;
}

std::string trace(const Recorded& run) {
  std::string text;
  char buffer[32];
  for (const NewtonReport& r : run.reports) {
    std::snprintf(buffer, sizeof buffer, " %.2e%s", r.gradient_measure, r.shifted ? "(s)" : "");
    text += buffer;
  }
  return text;
}

// e_{k+1} <= C e_k^2 in the local regime (e_k < 1e-2, e_{k+1} above the toys'
// gradient round-off 1e-12), with C = 1e3 for these O(1) toys.
void expect_quadratic_convergence(const Recorded& run, const std::string& name) {
  const ObservedOrders orders = observed_orders(run.measures());
  INFO(name << ": measures" << trace(run));
  REQUIRE(orders.pairs >= 1);
  CHECK(orders.max_quadratic_constant < 1e3);
  MESSAGE(name << ": " << run.result.iterations << " iterations, local pairs " << orders.pairs
               << ", max e_{k+1}/e_k^2 " << orders.max_quadratic_constant << ", min log ratio "
               << orders.min_log_ratio << ";" << trace(run));
}

}  // namespace

// Both globalizations: the default (energy line search) and KINSOL's line
// search with the energy fallback at indefinite Hessians.
std::vector<NewtonOptions> both_line_searches(int max_iterations = 100) {
  NewtonOptions energy = tight();
  energy.max_iterations = max_iterations;
  NewtonOptions kinsol = energy;
  kinsol.line_search = LineSearch::KinsolWithEnergyFallback;
  return {energy, kinsol};
}

std::string label(const NewtonOptions& options) {
  return options.line_search == LineSearch::Energy ? "energy line search"
                                                   : "KINSOL line search with energy fallback";
}

TEST_CASE("Newton converges quadratically on the chain") {
  for (NewtonOptions options : both_line_searches()) {
    options.max_chord_corrections = 0;  // Newton's own rate
    StencilObjective chain = make_chain();
    const Recorded run = run_newton(chain, options);
    INFO(label(options) << ": " << run.result.reason);
    REQUIRE(run.result.status == SolveStatus::Converged);
    CHECK(run.result.gradient_measure <= 1e-10);
    CHECK(run.result.stable);
    CHECK(run.result.iterations == static_cast<int>(run.reports.size()) - 1);
    CHECK(run.reports.front().iteration == 0);
    CHECK(run.result.factorizations >= run.result.iterations + 1);  // + stability check
    expect_quadratic_convergence(run, "chain, " + label(options));
  }
}

TEST_CASE("Newton converges on the extended Rosenbrock function") {
  // KINSOL's merit line search crawls along the curved valleys (|g|^2 is far
  // more curved across them than the energy): hence the iteration budget.
  for (NewtonOptions options : both_line_searches(500)) {
    options.max_chord_corrections = 0;  // Newton's own rate
    StencilObjective rosenbrock = make_rosenbrock(8);
    const Recorded run = run_newton(rosenbrock, options);
    INFO(label(options) << ": " << run.result.reason);
    REQUIRE(run.result.status == SolveStatus::Converged);
    CHECK((rosenbrock.get() - Eigen::VectorXd::Ones(8)).norm() < 1e-8);
    CHECK(run.result.stable);
    expect_quadratic_convergence(run, "rosenbrock, " + label(options));
  }
}

TEST_CASE("Newton on the offset (rebasing) objective") {
  StencilObjective plain = make_chain();
  REQUIRE(solve_newton(plain, tight()).converged());
  for (const NewtonOptions& options : both_line_searches()) {
    StencilObjective inner = make_chain();
    OffsetObjective offset(inner, 0.3);
    const Recorded run = run_newton(offset, options);
    INFO(label(options) << ": " << run.result.reason);
    REQUIRE(run.result.status == SolveStatus::Converged);
    CHECK(run.result.stable);
    CHECK(offset.rebases() ==
          run.result.iterations + 1);   // one before the first iteration, one after each
    CHECK(offset.get().norm() < 1e-6);  // offsets are reset every iteration
    expect_quadratic_convergence(run, "offset chain, " + label(options));
    CHECK((offset.configuration() - plain.get()).norm() < 1e-8 * plain.get().norm());
  }
}

TEST_CASE("Newton reaches a solution far beyond max_step in capped steps of doubling length") {
  const int n = 6;
  Eigen::MatrixXd K = Eigen::MatrixXd::Identity(n, n) * 2.0;
  K(0, 1) = K(1, 0) = 0.5;
  Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  f *= 1000.0 / K.ldlt().solve(f).norm();  // the solution 1000 steps of max_step away
  const Eigen::VectorXd solution = K.ldlt().solve(f);
  for (bool grow : {true, false}) {
    CAPTURE(grow);
    Quadratic objective(K, f);
    NewtonOptions options = tight();
    options.max_step = 1.0;
    options.grow_step_cap = grow;
    std::vector<double> steps;  // 2-norm of each step
    const NewtonResult r =
        solve_newton(objective, options, recording_step_lengths(objective, steps));
    CAPTURE(r.reason);
    if (!grow) {  // 1000 steps of max_step needed, more than the iteration limit
      CHECK(r.status == SolveStatus::IterationLimit);
      REQUIRE(steps.size() >= 2);
      CHECK(steps[1] == doctest::Approx(1.0).epsilon(1e-12));
      continue;
    }
    REQUIRE(r.converged());
    CHECK(r.iterations <= 13);  // about log2(1000) = 10
    REQUIRE(steps.size() >= 3);
    CHECK(steps[0] == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(steps[1] == doctest::Approx(2.0).epsilon(1e-12));
    CHECK(steps[2] == doctest::Approx(4.0).epsilon(1e-12));
    CHECK((objective.get() - solution).norm() < 1e-9 * solution.norm());
  }
}

TEST_CASE("Newton from a converged start does no iteration") {
  StencilObjective chain = make_chain();
  REQUIRE(solve_newton(chain, tight()).converged());
  const long evaluations = chain.evaluations();
  const Recorded run = run_newton(chain, tight());
  CHECK(run.result.status == SolveStatus::Converged);
  CHECK(run.result.iterations == 0);
  CHECK(run.reports.size() == 1);
  CHECK(run.result.stable);
  CHECK(run.result.factorizations == 1);  // the stability check only
  CHECK(chain.evaluations() - evaluations <= 4);
}

TEST_CASE("a NewtonSolver keeps its symbolic analysis across solves") {
  StencilObjective chain = make_chain();
  NewtonSolver solver(chain, tight());
  REQUIRE(solver.solve().converged());
  const CholeskyStats first = solver.cholesky_stats();
  Eigen::VectorXd q = chain.get();
  q[4] += 0.01;  // a new load step, say
  chain.set(q);
  const NewtonResult again = solver.solve();
  REQUIRE(again.converged());
  CHECK(again.iterations >= 1);
  CHECK(solver.cholesky_stats().analyses == 1);
  CHECK(solver.cholesky_stats().factorizations == first.factorizations + again.factorizations);
}

TEST_CASE("a NewtonSolver lends and takes back its CHOLMOD solver, analysis and factorization") {
  StencilObjective chain = make_chain();
  CholeskySolver taken;
  {
    NewtonSolver solver(chain, tight());
    REQUIRE(solver.solve().converged());
    solver.swap_cholesky(taken);
    CHECK(solver.cholesky_stats().analyses == 0);  // it holds the empty one now
  }
  // The final state's Hessian, factorized by the stability test: again is
  // no new factorization.
  const CholeskyStats after_solve = taken.stats();
  CHECK(after_solve.analyses == 1);
  CHECK(taken.factorize(chain.hessian()) == FactorizationStatus::PositiveDefinite);
  CHECK(taken.stats().factorizations == after_solve.factorizations);

  // Lent to another solver of the same pattern: no analysis of its own.
  Eigen::VectorXd q = chain.get();
  q[4] += 0.01;
  chain.set(q);
  NewtonSolver other(chain, tight());
  other.swap_cholesky(taken);
  const NewtonResult again = other.solve();
  REQUIRE(again.converged());
  CHECK(again.iterations >= 1);
  CHECK(other.cholesky_stats().analyses == 1);
  CHECK(other.cholesky_stats().factorizations == after_solve.factorizations + again.factorizations);
  other.swap_cholesky(taken);
  CHECK(taken.stats().factorizations == after_solve.factorizations + again.factorizations);
}

TEST_CASE("Newton on the Euler column: saddle versus buckled minimum") {
  ColumnOptions straight;
  SUBCASE("started on the symmetric (straight) line, it converges to the saddle") {
    // With the escape off (it is on by default: saddle_escape_test.cpp).
    NewtonOptions options = tight();
    options.escape.enabled = false;
    StencilObjective column = make_column(straight);
    const Recorded run = run_newton(column, options);
    INFO(run.result.reason);
    REQUIRE(run.result.status == SolveStatus::Converged);
    CHECK(std::abs(column.get()[column_middle_y(straight)]) < 1e-12);
    CHECK_FALSE(run.result.stable);  // never call a saddle stable
    MESSAGE("straight column: " << run.result.iterations << " iterations");

    // Restarted exactly at the saddle: converged at once, still unstable.
    const Recorded again = run_newton(column, options);
    CHECK(again.result.status == SolveStatus::Converged);
    CHECK(again.result.iterations == 0);
    CHECK_FALSE(again.result.stable);
  }
  SUBCASE("with an imperfection, it reaches the buckled minimum") {
    ColumnOptions imperfect = straight;
    imperfect.imperfection = 0.05;
    std::vector<Eigen::VectorXd> minima;
    for (const NewtonOptions& options : both_line_searches()) {
      StencilObjective column = make_column(imperfect);
      const Recorded run = run_newton(column, options);
      INFO(label(options) << ": " << run.result.reason);
      REQUIRE(run.result.status == SolveStatus::Converged);
      CHECK(run.result.stable);
      CHECK(column.get()[column_middle_y(imperfect)] > 0.05);  // buckled, same side
      bool any_shift = false;
      for (const NewtonReport& r : run.reports) {
        any_shift = any_shift || r.shifted;
        if (options.line_search == LineSearch::Energy)
          CHECK(r.energy_line_search == (r.iteration > 0));
      }
      CHECK(any_shift);  // the start is close enough to the saddle to need a shift
      expect_quadratic_convergence(run, "buckled column, " + label(options));
      minima.push_back(column.get());
    }
    CHECK((minima[0] - minima[1]).norm() < 1e-8);
  }
}

TEST_CASE("KINSOL's merit line search alone stalls on an indefinite start") {
  // The chain starts compressed: its Hessian is indefinite and the shifted
  // step is an energy descent direction but not one of |g|^2.
  StencilObjective chain = make_chain();
  NewtonOptions kinsol_only = tight();
  kinsol_only.line_search = LineSearch::Kinsol;
  const Recorded run = run_newton(chain, kinsol_only);
  MESSAGE("LineSearch::Kinsol on the chain: " << std::string(describe(run.result.status)) << " ("
                                              << run.result.reason << ") after "
                                              << run.result.iterations << " iterations");
  CHECK(run.result.status == SolveStatus::LineSearchFailed);
  REQUIRE(run.reports.size() >= 1);
  CHECK(std::isfinite(chain.energy()));  // left at the last accepted iterate

  StencilObjective fresh = make_chain();
  NewtonOptions with_fallback = tight();
  with_fallback.line_search = LineSearch::KinsolWithEnergyFallback;
  const Recorded fallback = run_newton(fresh, with_fallback);
  CHECK(fallback.result.status == SolveStatus::Converged);
  bool used_fallback = false;
  for (const NewtonReport& r : fallback.reports)
    used_fallback = used_fallback || r.energy_line_search;
  CHECK(used_fallback);
}

TEST_CASE("Newton stops when the stop flag is raised") {
  StencilObjective rosenbrock = make_rosenbrock(8);
  std::atomic<bool> stop{false};
  NewtonCallbacks callbacks;
  int reports = 0;
  callbacks.on_iteration = [&](const NewtonReport& r) {
    ++reports;
    if (r.iteration == 2) stop = true;
  };
  callbacks.stop = &stop;
  const NewtonResult result = solve_newton(rosenbrock, tight(), callbacks);
  CHECK(result.status == SolveStatus::Interrupted);
  CHECK(result.iterations == 2);
  CHECK(reports == 3);
  CHECK(std::isfinite(rosenbrock.energy()));
}

TEST_CASE("Newton handles invalid configurations and non-finite values") {
  const Eigen::VectorXd start = Eigen::VectorXd::Constant(3, 4.0);
  // The full Newton step from x = 4 lands at x = -4 (invalid), half of it at 0.
  for (const NewtonOptions& options : both_line_searches()) {
    INFO(label(options));
    SUBCASE("domain_error at a trial point: backtracks and converges") {
      SqrtWell well(start, InvalidBehaviour::Throw);
      const NewtonResult result = solve_newton(well, options);
      INFO(result.reason);
      CHECK(result.status == SolveStatus::Converged);
      CHECK(well.invalid_encounters() >= 2);
      CHECK((well.get() - Eigen::VectorXd::Ones(3)).norm() < 1e-8);
    }
    SUBCASE("NaN at a trial point: backtracks and converges") {
      SqrtWell well(start, InvalidBehaviour::NaN);
      const NewtonResult result = solve_newton(well, options);
      INFO(result.reason);
      CHECK(result.status == SolveStatus::Converged);
      CHECK(well.invalid_encounters() >= 2);
    }
    SUBCASE("a NaN region between the start and the minimum stops the solve") {
      SqrtWell well(start, InvalidBehaviour::NaN, 3.9);  // the minimum x = 1 is unreachable
      const NewtonResult result = solve_newton(well, options);
      INFO(result.reason);
      CHECK(well.invalid_encounters() >= 5);
      CHECK(std::isfinite(well.energy()));  // left at the last accepted iterate
      CHECK((well.get().array() >= 3.9).all());
      if (options.line_search == LineSearch::Energy) {
        // Backtracks into the valid sliver [3.9, 4], then stagnates at its edge.
        CHECK(result.status == SolveStatus::LineSearchFailed);
        CHECK(result.iterations >= 1);
      } else {
        // KINSOL halves a failing step at most 5 times: every trial is NaN.
        CHECK(result.status == SolveStatus::NonFinite);
        CHECK(result.iterations == 0);
        CHECK(well.get() == start);
      }
    }
    SUBCASE("invalid configurations around the start: LineSearchFailed") {
      SqrtWell well(start, InvalidBehaviour::Throw, 3.9);
      const NewtonResult result = solve_newton(well, options);
      INFO(result.reason);
      CHECK(result.status == SolveStatus::LineSearchFailed);
      CHECK((well.get().array() >= 3.9).all());
    }
    SUBCASE("NaN at the start: NonFinite without any iteration") {
      SqrtWell well(Eigen::VectorXd::Constant(3, -1.0), InvalidBehaviour::NaN);
      const NewtonResult result = solve_newton(well, options);
      CHECK(result.status == SolveStatus::NonFinite);
      CHECK(result.iterations == 0);
      CHECK_FALSE(result.stable);
    }
  }
}

TEST_CASE("Newton stops at the round-off floor instead of iterating forever") {
  StencilObjective chain = make_chain();
  NewtonOptions options = tight();
  options.gradient_tolerance = 1e-300;  // below any achievable gradient
  const NewtonResult result = solve_newton(chain, options);
  INFO(result.reason);
  CHECK(result.status == SolveStatus::LineSearchFailed);
  CHECK(result.iterations < 30);
  CHECK(result.gradient_measure < 1e-12);
  CHECK(result.stable);
}

TEST_CASE("an unexpected exception inside a KINSOL callback reaches the caller") {
  StencilObjective chain = make_chain();
  FaultyObjective faulty(chain, 3);  // throws inside KINSOL's line search (residual calls)
  NewtonOptions options = tight();
  options.line_search = LineSearch::Kinsol;  // every trial point comes from KINSOL
  CHECK_THROWS_AS(solve_newton(faulty, options), std::runtime_error);
  CHECK(faulty.calls() >= 3);
}

}  // namespace xshell::test::newton_test
