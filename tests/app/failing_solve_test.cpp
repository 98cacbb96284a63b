// Failing solves through the real program: each ends with exit status 3, a
// last stderr line "xshell: STATUS after N iterations: REASON; ..." (one
// line), a summary saying it did not converge and why, and the last good
// state written (a state that --init accepts). The solvers' own tests cover
// the same failures on toy objectives, including NaN appearing mid-solve
// (tests/integrators/test_newton.cpp, test_dynamics.cpp).
#include <doctest/doctest.h>

#include <cmath>

#include "reliability_support.hpp"

namespace xshell::test {

namespace {

struct Failed {
  CommandResult run;
  nlohmann::json summary;
};

// Runs `config` (writing to `dir`/out) and checks everything a failed solve
// must leave: status 3, one last line naming `status` and the reason, a
// complete summary and state, a closed series.
Failed run_failing(const ScratchDirectory& dir, const std::string& config,
                   const std::string& status) {
  write_text(dir / "run.json", config);
  Failed f;
  f.run = run_xshell("relax run.json", dir.path());
  INFO("stderr: " << f.run.errors);
  CHECK(f.run.status == 3);
  const std::string line = last_line(f.run.errors);
  CHECK(line.rfind("xshell: " + status + " after ", 0) == 0);
  REQUIRE(fs::exists(dir / "out" / "summary.json"));
  f.summary = read_json(dir / "out" / "summary.json");
  CHECK(f.summary["status"] == status);
  CHECK(f.summary["converged"] == false);
  CHECK(f.summary["interrupted"] == false);
  const std::string reason = f.summary["reason"];
  CHECK_FALSE(reason.empty());
  CHECK(reason.find('\n') == std::string::npos);
  CHECK(contains(line, reason));
  // The state and the series are complete, nothing is left half-written.
  CHECK(read_json(dir / "out" / "state.json")["format"] == "xshell-state");
  CHECK(check_outputs_complete(dir / "out") >= 6);
  CHECK(temporary_files(dir / "out").empty());
  return f;
}

// The written state is the one the summary describes, and a good start:
// --init from it, with the limits lifted, runs (and the first recorded
// energy is the summary's).
void check_restart(const ScratchDirectory& dir, const nlohmann::json& summary,
                   int expected_status = 0) {
  write_text(dir / "again.json", sample_config(dir / "again"));
  const CommandResult r = run_xshell("relax again.json --init out/state.json", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == expected_status);
  const nlohmann::json again = read_json(dir / "again" / "summary.json");
  CHECK(again["history"][0]["energy"].get<double>() ==
        doctest::Approx(summary["energy"]["total"].get<double>()).epsilon(1e-9));
}

}  // namespace

TEST_CASE("failing solve: Newton's iteration limit") {
  ScratchDirectory dir("fail-iterations");
  const Failed f = run_failing(
      dir, sample_config(dir / "out", R"(, "solver": {"max_iterations": 1})"), "max_iterations");
  CHECK(f.summary["reason"] == "no convergence in 1 iterations");
  CHECK(f.summary["iterations"] == 1);
  CHECK(f.summary["gradient_norm"].get<double>() > f.summary["gradient_tolerance"].get<double>());
  // The state is the iterate after the one iteration, not the start.
  CHECK(f.summary["energy"]["total"].get<double>() < 0.0);
  CHECK(f.summary["energy"]["total"].get<double>() ==
        doctest::Approx(f.summary["history"][1]["energy"].get<double>()));
  check_restart(dir, f.summary);
}

TEST_CASE("failing solve: damped dynamics' step limit") {
  ScratchDirectory dir("fail-steps");
  const Failed f = run_failing(
      dir, sample_config(dir / "out", R"(, "solver": {"method": "dynamics", "max_steps": 3})"),
      "max_iterations");
  CHECK(f.summary["reason"] == "no convergence in 3 steps");
  CHECK(f.summary["iterations"] == 3);
  CHECK(f.summary["simulated_time"].get<double>() > 0.0);
  check_restart(dir, f.summary);
}

TEST_CASE("failing solve: a line search that cannot progress (tolerance below round-off)") {
  ScratchDirectory dir("fail-line-search");
  const Failed f =
      run_failing(dir, sample_config(dir / "out", R"(, "solver": {"gradient_tolerance": 1e-300})"),
                  "line_search_failed");
  CHECK(contains(f.summary["reason"], "stagnation"));
  // It stopped at the round-off floor, in equilibrium for any sane tolerance.
  CHECK(f.summary["gradient_norm"].get<double>() < 1e-6);
  CHECK(f.summary["iterations"].get<int>() < 30);
  check_restart(dir, f.summary);
}

TEST_CASE("failing solve: a gradient that is not finite (gravity times density overflows)") {
  ScratchDirectory dir("fail-non-finite");
  std::string text = sample_config(dir / "out", R"(, "solver": {"max_iterations": 10})");
  const std::size_t density = text.find("\"density\": 1800");
  REQUIRE(density != std::string::npos);
  text.replace(density, 15, "\"density\": 1e300");
  const std::size_t gravity = text.find("[0, 0, -9.81]");
  REQUIRE(gravity != std::string::npos);
  text.replace(gravity, 13, "[0, 0, -1e20]");
  write_text(dir / "run.json", text);
  const CommandResult r = run_xshell("relax run.json", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 3);
  CHECK(last_line(r.errors).rfind("xshell: non_finite after 0 iterations: ", 0) == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["status"] == "non_finite");
  CHECK(contains(s["reason"], "not finite"));
  CHECK(s["converged"] == false);
  CHECK(s["stable"].is_null());  // not converged: no claim
  // The last good state is the start: every vertex where the file put it.
  const nlohmann::json start = read_json(dir / "out" / "state.json");
  CHECK(start["format"] == "xshell-state");
  CHECK(s["vertices"][13][0].get<double>() == doctest::Approx(0.125));
  CHECK(s["vertices"][13][2].get<double>() == 0.0);
  CHECK(check_outputs_complete(dir / "out") >= 6);
}

TEST_CASE("failing solve: damped dynamics under a force of 1e30 stops as diverged") {
  ScratchDirectory dir("fail-diverged");
  // Before: every step to the limit (past 120 s on a large linkage, the
  // energy at -3.6e36).
  std::string text = sample_config(dir / "out", R"(, "solver": {"method": "dynamics"})");
  const std::size_t force = text.find("[0, 0, -5.0]");
  REQUIRE(force != std::string::npos);
  text.replace(force, 12, "[0, 0, -1e30]");
  const Failed f = run_failing(dir, text, "diverged");
  CHECK(contains(f.summary["reason"], "diverging: over the last 1000 steps"));
  CHECK(f.summary["iterations"].get<long>() == 1000);
}

TEST_CASE("failing solve: a singular system (supports that leave rigid motions free)") {
  ScratchDirectory dir("fail-singular");
  // Three z rollers: the grid may slide and turn in its plane, and a
  // horizontal force pushes it along x: no equilibrium exists.
  const Failed f = run_failing(dir, config_with(grid_obj(), R"(, "solver": {"max_iterations": 4},
  "supports": [{"vertex": 0, "fix": ["z"]}, {"vertex": 5, "fix": ["z"]}, {"vertex": 27, "fix": ["z"]}],
  "loads": {"forces": [{"vertex": 13, "force": [1, 0, 0]}]})"),
                               "max_iterations");
  const std::string reason = f.summary["reason"];
  CHECK(reason.rfind("singular system: the supports leave rigid motions free (translation along x; "
                     "translation along y; rotation about z through (",
                     0) == 0);
  CHECK(contains(reason, "no convergence in 4 iterations"));
  CHECK(f.summary["stable"].is_null());  // not converged: no claim
  CHECK(contains(f.run.errors, "xshell: warning: the supports leave rigid motions free ("));
}

TEST_CASE("relax: free rigid motions that nothing pushes: a warning, converged, not stable") {
  ScratchDirectory dir("free-unloaded");
  write_text(dir / "run.json", config_with(grid_obj(), R"(,
  "supports": [{"vertex": 0, "fix": ["z"]}, {"vertex": 5, "fix": ["z"]}, {"vertex": 27, "fix": ["z"]}])"));
  const CommandResult r = run_xshell("relax run.json", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 0);
  CHECK(contains(r.errors,
                 "xshell: warning: the supports leave rigid motions free (translation along x"));
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["converged"] == true);
  CHECK(s["stable"] == false);  // a mechanism: it slides without any force
}

}  // namespace xshell::test
