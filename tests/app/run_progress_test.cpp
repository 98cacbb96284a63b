// The progress styles (app/run_progress.hpp), written into a temporary file.
#include "app/run_progress.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace xshell::test {

namespace {

// What `style` prints for a phase, `samples` iterations and the finish.
std::vector<std::string> printed(ProgressStyle style, int samples, bool own_line = false) {
  std::FILE* file = std::tmpfile();
  REQUIRE(file != nullptr);
  {
    RunProgress progress(style, RunProgress::Clock::now(), file);
    progress.phase("solve");
    for (int k = 0; k < samples; ++k)
      progress.sample({"solve", "newton", k, 1.5, 1e-3, std::nullopt, std::nullopt}, own_line);
    RunTimings t;
    t.solve = 0.25;
    progress.finish("converged", t, 0.5);
  }
  std::rewind(file);
  std::vector<std::string> lines;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, file)) {
    std::string line = buffer;
    if (!line.empty() && line.back() == '\n') line.pop_back();
    lines.push_back(line);
  }
  std::fclose(file);
  return lines;
}

}  // namespace

TEST_CASE("progress json: one object per line, every iteration, the times last") {
  const std::vector<std::string> lines = printed(ProgressStyle::Json, 3);
  REQUIRE(lines.size() == 5);  // the phase, 3 iterations, done
  const nlohmann::json phase = nlohmann::json::parse(lines[0]);
  CHECK(phase["event"] == "phase");
  CHECK(phase["phase"] == "solve");
  for (int k = 1; k <= 3; ++k) {
    const nlohmann::json j = nlohmann::json::parse(lines[k]);
    CHECK(j["event"] == "iteration");
    CHECK(j["phase"] == "solve");
    CHECK(j["iteration"] == k - 1);
    CHECK(j["energy"] == 1.5);
    CHECK(j["gradient"] == 1e-3);
    CHECK(j["elapsed"].get<double>() >= 0.0);
  }
  const nlohmann::json done = nlohmann::json::parse(lines[4]);
  CHECK(done["event"] == "done");
  CHECK(done["status"] == "converged");
  CHECK(done["timings"]["solve"] == 0.25);
  CHECK(done["elapsed"] == 0.5);
}

TEST_CASE("progress plain: phases, at most one iteration line per interval, the times last") {
  // A thousand iterations within far less than kPlainInterval: one line.
  const std::vector<std::string> lines = printed(ProgressStyle::Plain, 1000);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].rfind("xshell: solve (", 0) == 0);
  CHECK(lines[1].rfind("xshell: solve newton: iteration 0, energy 1.500000e+00", 0) == 0);
  CHECK(lines[2].rfind("xshell: times: load 0.00 s, setup 0.00 s, solve 0.25 s", 0) == 0);
}

TEST_CASE("progress text: iterations only where the caller prints none of its own") {
  CHECK(printed(ProgressStyle::Text, 4).size() == 2);        // the phase, the times
  CHECK(printed(ProgressStyle::Text, 4, true).size() == 6);  // and the 4 iterations
  CHECK(printed(ProgressStyle::Off, 4, true).empty());
}

TEST_CASE("progress style: the command line, then the configuration, then the terminal") {
  CHECK(resolve_progress(ProgressStyle::Json, Toggle::Off, true) == ProgressStyle::Json);
  CHECK(resolve_progress(std::nullopt, Toggle::On, false) == ProgressStyle::Text);
  CHECK(resolve_progress(std::nullopt, Toggle::Off, true) == ProgressStyle::Off);
  CHECK(resolve_progress(std::nullopt, Toggle::Auto, true) == ProgressStyle::Text);
  CHECK(resolve_progress(std::nullopt, Toggle::Auto, false) == ProgressStyle::Plain);
  CHECK_FALSE(parse_progress_style("auto"));
  CHECK(parse_progress_style("json") == ProgressStyle::Json);
  CHECK(parse_progress_style("off") == ProgressStyle::Off);
  CHECK_THROWS_AS(parse_progress_style("loud"), std::invalid_argument);
}

}  // namespace xshell::test
