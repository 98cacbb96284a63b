// Kinetic damping through the real program on the sample (validation
// suite: seconds each on a loaded machine): a tolerance below the round-off
// floor stops on stagnation and a force of 1e30 on divergence, each with
// exit 3, the status the other solvers use and a summary.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "bad_input_support.hpp"

namespace xshell::test {

namespace {

struct Stopped {
  CommandResult command;
  nlohmann::json summary;
  double seconds = 0.0;
};

// Runs the sample by kinetic damping with `solver` settings and `loads`
// instead of its own, killed after 120 s.
Stopped run_sample(const ScratchDirectory& dir, const std::string& solver,
                   const std::string& loads) {
  std::string config = replacing(sample_config("out", R"(, "solver": )" + solver),
                                 R"("subdivisions": 6)", R"("subdivisions": 8)");
  if (!loads.empty()) config = replacing(config, R"({"vertex": 13, "force": [0, 0, -5.0]})", loads);
  write_text(dir / "run.json", config);
  ::setenv("OMP_NUM_THREADS", "1", 1);  // small linkage: threads only spin
  const auto start = std::chrono::steady_clock::now();
  Stopped s;
  s.command = run_xshell_limited("relax run.json --quiet", dir.path(), 120);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (fs::exists(dir / "out" / "summary.json")) s.summary = read_json(dir / "out" / "summary.json");
  return s;
}

}  // namespace

TEST_CASE("kinetic damping: a tolerance of 1e-30 on the sample stops on stagnation" *
          doctest::test_suite("validation")) {
  // Before: killed after 120 s, at some 16,000 of 1,000,000 iterations.
  ScratchDirectory dir("kd-stagnation");
  const Stopped s =
      run_sample(dir, R"({"method": "kinetic-damping", "gradient_tolerance": 1e-30})", "");
  INFO("stderr: " << s.command.errors);
  CHECK(s.command.status == 3);
  REQUIRE(s.summary.is_object());
  CHECK(s.summary["status"] == "integrator_failed");
  CHECK(s.summary["reason"].get<std::string>().rfind("stagnation: over the last ", 0) == 0);
  CHECK(s.summary["iterations"].get<long>() < 100000);
  CHECK(check_outputs_complete(dir / "out") >= 6);
  MESSAGE("sample, tolerance 1e-30: " << s.summary["iterations"] << " iterations, " << s.seconds
                                      << " s: " << s.summary["reason"]);
}

TEST_CASE("kinetic damping: a force of 1e30 on the sample stops as diverged" *
          doctest::test_suite("validation")) {
  // Before: killed after 120 s, the energy at 1.5e54 and the gradient growing.
  ScratchDirectory dir("kd-divergence");
  const Stopped s = run_sample(dir, R"({"method": "kinetic-damping"})",
                               R"({"vertex": 30, "force": [1e30, 0, -1e30]})");
  INFO("stderr: " << s.command.errors);
  CHECK(s.command.status == 3);
  REQUIRE(s.summary.is_object());
  CHECK(s.summary["status"] == "diverged");
  CHECK(s.summary["reason"].get<std::string>().rfind("diverging: over the last 2000 iterations",
                                                     0) == 0);
  CHECK(s.summary["iterations"].get<long>() < 20000);
  MESSAGE("sample, force 1e30 at vertex 30: " << s.summary["iterations"] << " iterations, "
                                              << s.seconds << " s");
}

}  // namespace xshell::test
