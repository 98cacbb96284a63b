// The status names are an interface: summary.json's "status" and the
// deployment's reason carry them, and tools read them.
#include "integrators/common/solve_result.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <set>
#include <string>
#include <vector>

namespace xshell::test {

namespace {

// Every status with its summary name and its words.
struct Named {
  SolveStatus status;
  std::string name;
  std::string words;
};

const std::vector<Named>& every_status() {
  static const std::vector<Named> all = {
      {SolveStatus::Converged, "converged", "converged"},
      {SolveStatus::IterationLimit, "max_iterations", "maximum number of iterations reached"},
      {SolveStatus::LinearSolverFailed, "linear_solver_failed", "linear solver failed"},
      {SolveStatus::LineSearchFailed, "line_search_failed", "line search failed"},
      {SolveStatus::IntegratorFailed, "integrator_failed", "integrator failed"},
      {SolveStatus::InvalidConfiguration, "invalid_configuration", "invalid configurations"},
      {SolveStatus::NonFinite, "non_finite", "non-finite values"},
      {SolveStatus::Interrupted, "interrupted", "interrupted"},
      {SolveStatus::StepFailed, "step_failed", "step failed"},
      {SolveStatus::Diverged, "diverged", "diverging"},
  };
  return all;
}

}  // namespace

TEST_CASE("every solve status has its summary name and its words") {
  std::set<std::string> names;
  for (const Named& n : every_status()) {
    CAPTURE(n.name);
    CHECK(std::string(to_string(n.status)) == n.name);
    CHECK(std::string(describe(n.status)) == n.words);
    names.insert(to_string(n.status));
  }
  // The list covers the enum: its values are 0 .. Diverged, all distinct.
  CHECK(every_status().size() == static_cast<size_t>(SolveStatus::Diverged) + 1);
  CHECK(names.size() == every_status().size());
}

TEST_CASE("a solve result is converged exactly when its status is Converged") {
  int checked = 0;
  for (const Named& n : every_status()) {
    SolveResult r;
    r.status = n.status;
    CHECK(r.converged() == (n.status == SolveStatus::Converged));
    ++checked;
  }
  CHECK(checked == 10);
  CHECK(SolveResult{}.status == SolveStatus::IterationLimit);
}

TEST_CASE("the stop flag comes before the iteration limit") {
  std::atomic<bool> stop{false};
  SolveResult r;
  CHECK_FALSE(stop_or_limit(&stop, 4, 5, "iterations", r));
  CHECK_FALSE(stop_or_limit(nullptr, 4, 5, "iterations", r));
  CHECK(r.reason.empty());
  CHECK(stop_or_limit(&stop, 5, 5, "steps", r));
  CHECK(r.status == SolveStatus::IterationLimit);
  CHECK(r.reason == "no convergence in 5 steps");
  stop = true;
  CHECK(stop_or_limit(&stop, 5, 5, "iterations", r));
  CHECK(r.status == SolveStatus::Interrupted);
  CHECK(r.reason == "stop flag raised");
}

TEST_CASE("numbers in reasons have four significant digits") {
  CHECK(scientific(1.0) == "1.000e+00");
  CHECK(scientific(-2.5e-9) == "-2.500e-09");
}

}  // namespace xshell::test
