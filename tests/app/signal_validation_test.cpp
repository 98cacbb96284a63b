// SIGTERM in the middle of a long iteration (validation suite: the model
// takes a while to set up): the run ends within the grace period and a few
// seconds, with a summary that says so and a state that restarts the run.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "reliability_support.hpp"
#include "skip.hpp"

namespace xshell::test {

namespace {

// The largest design (1,371 joints) in millimetres, 10 edges per segment,
// relaxed from straight by Newton: seconds to the first iteration's state,
// then iterations of 0.3 s (a quiet machine) to several seconds (a loaded
// one), a batch job's typical victim.
std::string large_design(const fs::path& obj, int max_iterations) {
  return R"({
  "linkage": ")" +
         obj.string() +
         R"(",
  "subdivisions": 10,
  "rest_shape": "straight",
  "material": {"young_modulus": 20000, "poisson_ratio": 0.3, "density": 1,
               "cross_section": {"shape": "rectangle", "width": 10, "height": 7}},
  "solver": {"max_iterations": )" +
         std::to_string(max_iterations) + R"(},
  "output": {"directory": "out"}
})";
}

}  // namespace

TEST_CASE("interrupt: SIGTERM during a long iteration ends the run within the grace period" *
          doctest::test_suite("validation")) {
  const fs::path obj = fs::path(XSHELL_SHARED_DATA_DIR) / "large_6d35a972.obj";
  if (!fs::exists(obj)) XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  ScratchDirectory dir("sigterm-long-iteration");
  write_text(dir / "run.json", large_design(obj, 1000));
  // A grace period shorter than an iteration, so that the signal usually
  // finds the iteration in progress when it runs out.
  const double grace = 0.1;
  RelaxProcess run(dir / "run.json", dir.path(), {"--grace", "0.1"});
  REQUIRE(run.started());
  const auto started = std::chrono::steady_clock::now();
  // The first iteration's state is written, then the second begins (the
  // solver's set-up, between the starting state and the first iteration,
  // is as long but not an iteration).
  REQUIRE(run.wait_for(dir / "out" / "rods_000001.vtp", std::chrono::seconds(300)));
  const double first =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // into the second iteration
  const auto sent = std::chrono::steady_clock::now();
  run.signal(SIGTERM);
  const int raw = run.wait(std::chrono::seconds(120));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  INFO("stderr: " << run.errors());
  REQUIRE(raw != -1);
  REQUIRE(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 130);
  // The grace period and the write of the last state (4.9 MB: up to 3.5 s
  // on a loaded machine).
  CHECK(seconds < grace + 4.9);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["status"] == "interrupted");
  CHECK(s["interrupted"] == true);
  // The grace period ran out (the iteration in progress outlasted it: the
  // last written step was saved), or the iteration ended within it (the
  // run's own interrupted ending); either way promptly, as checked above.
  const bool ran_out = contains(s["reason"], "did not end within the grace period (0.1 s)");
  CHECK((ran_out || contains(s["reason"], "interrupted by a signal")));
  const double energy = s["energy"]["total"].get<double>();
  CHECK(std::isfinite(energy));
  CHECK(check_outputs_complete(dir / "out") >= 4);
  CHECK(temporary_files(dir / "out").empty());
  MESSAGE("large design, 10 edges per segment: first iteration written after "
          << first << " s; SIGTERM 0.02 s into the second, exit 130 after " << seconds
          << " s (grace " << grace << " s, " << std::string(ran_out ? "ran out" : "not needed")
          << ")");

  // The saved state restarts the run where it was: one iteration from it
  // starts at the summary's energy.
  write_text(dir / "again.json", large_design(obj, 1));
  const CommandResult again =
      run_xshell("relax again.json --init out/state.json --out again --quiet", dir.path());
  CAPTURE(again.errors);
  CHECK(again.status == 3);
  CHECK(read_json(dir / "again" / "summary.json")["history"][0]["energy"].get<double>() ==
        doctest::Approx(energy).epsilon(1e-9));
}

}  // namespace xshell::test
