// What a run reports, through the real program: the summary's timings,
// `--progress json` on stderr and the analysis' time budget (a deployment's
// series timed by its average opening angle: deploy_command_test.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <vector>

#include "reliability_support.hpp"

namespace xshell::test {

namespace {

std::vector<nlohmann::json> json_lines(const std::string& text) {
  std::vector<nlohmann::json> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line.front() == '{') out.push_back(nlohmann::json::parse(line));
  return out;
}

// The sample (run.json, writing to "out") run with `options`.
CommandResult run_sample(const ScratchDirectory& dir, const std::string& options,
                         const std::string& extra = "") {
  write_text(dir / "run.json", sample_config("out", extra));
  return run_xshell("relax run.json " + options, dir.path());
}

}  // namespace

TEST_CASE("run report: timings are finite, non-negative and add up to at most the wall time") {
  ScratchDirectory dir("report-timings");
  const CommandResult r = run_sample(dir, "--quiet");
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  CHECK(count_lines(r.errors) == 1);  // --quiet: only the outcome
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  const nlohmann::json& t = s["timings"];
  double sum = 0.0;
  for (const char* phase : {"load", "setup", "solve", "analysis", "output"}) {
    CAPTURE(phase);
    REQUIRE(t.contains(phase));
    const double seconds = t[phase].get<double>();
    CHECK(std::isfinite(seconds));
    CHECK(seconds >= 0.0);
    sum += seconds;
  }
  CHECK(t["solve"].get<double>() > 0.0);
  CHECK(t["analysis"].get<double>() > 0.0);  // converged: the stability analysis ran
  CHECK(t["output"].get<double>() > 0.0);
  CHECK(sum <= s["wall_seconds"].get<double>());
}

TEST_CASE("run report: --progress json prints an object per line, the times last") {
  ScratchDirectory dir("report-json");
  const CommandResult r = run_sample(dir, "--progress json");
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const std::vector<nlohmann::json> lines = json_lines(r.errors);
  REQUIRE(lines.size() >= 4);
  int iterations = 0, analysis_stages = 0;
  for (const nlohmann::json& j : lines) {
    CHECK(j.contains("phase"));
    CHECK(j["elapsed"].get<double>() >= 0.0);
    if (j["event"] == "iteration" && j["phase"] == "solve") {
      ++iterations;
      CHECK(j["iteration"].is_number_integer());
      CHECK(j["energy"].is_number());
      CHECK(j["gradient"].is_number());
    }
    if (j["event"] == "phase" && j["phase"] == "analysis") ++analysis_stages;
  }
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(iterations == s["iterations"].get<int>() + 1);  // the start and every iteration
  // Eigen modes, the unloaded equilibrium, buckling, and the check of its
  // estimate (the sample's grid hangs from four pins: its weight stiffens
  // it, and the check refutes the linear estimate).
  CHECK(s["stability_analysis"]["buckling"] == "refuted");
  CHECK(analysis_stages == 4);
  CHECK(lines.back()["event"] == "done");
  CHECK(lines.back()["timings"] == s["timings"]);
  // Only JSON before the outcome line.
  CHECK(static_cast<int>(lines.size()) == count_lines(r.errors) - 1);
  CHECK(contains(last_line(r.errors), "xshell: converged"));
}

TEST_CASE("run report: without a terminal the default is a few plain lines, never silent") {
  ScratchDirectory dir("report-plain");
  write_text(dir / "run.json", sample_config("out"));
  const CommandResult r = run_xshell("relax run.json", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  CHECK(contains(r.errors, "xshell: solve ("));
  CHECK(contains(r.errors, "xshell: analysis eigen_modes ("));
  CHECK(contains(r.errors, "xshell: times: load "));
  CHECK(count_lines(r.errors) < 15);
  // --verbose: a line per iteration.
  const CommandResult verbose = run_xshell("relax run.json --verbose", dir.path());
  CHECK(contains(verbose.errors, "newton    1  energy"));
  // Contradicting options are a usage error.
  CHECK(run_xshell("relax run.json --quiet --progress json", dir.path()).status == 2);
  CHECK(run_xshell("relax run.json --progress loud", dir.path()).status == 2);
}

TEST_CASE("run report: the analysis' time budget stops it with the status time_limit") {
  ScratchDirectory dir("report-budget");
  const CommandResult r = run_sample(dir, "--quiet", R"(, "analysis": {"max_seconds": 1e-9})");
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);  // the equilibrium converged; its analysis was cut short
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["stability_analysis"]["eigenvalues"] == "time_limit");
  CHECK(s["stability_analysis"]["buckling"] == "time_limit");
  CHECK(s["lowest_eigenvalues"].empty());
  CHECK(s["buckling_load_factor"].is_null());
  CHECK(contains(s["warnings"].dump(), "analysis.max_seconds"));
  CHECK(s["configuration"]["analysis"]["max_seconds"] == 1e-9);
  // Without a budget, and with fewer modes.
  REQUIRE(run_sample(dir, "--quiet", R"(, "analysis": {"max_seconds": null, "modes": 2})").status ==
          0);
  const nlohmann::json full = read_json(dir / "out" / "summary.json");
  CHECK(full["stability_analysis"]["eigenvalues"] == "converged");
  CHECK(full["lowest_eigenvalues"].size() == 2);
  CHECK(full["configuration"]["analysis"]["max_seconds"].is_null());
}

}  // namespace xshell::test
