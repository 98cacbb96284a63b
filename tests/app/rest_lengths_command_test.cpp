// "rest_lengths" through the program: relax and deploy to the given lengths,
// fabricate with them, refuse a state saved with others, and refuse bad
// values with status 2.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>

#include "command_runner.hpp"
#include "io/obj_reader.hpp"

namespace xshell::test {

namespace {

// One straight lath drawn 1 long on the x axis, vertex 0 held in position,
// vertex 1 on a roller along x (the twist about the axis stays free: no
// load acts on it). `extra`: more keys.
std::string lath_config(const std::string& extra) {
  return R"({"linkage": "lath.obj", "subdivisions": 5, "rest_shape": "straight",
  "material": {"young_modulus": 2e4, "cross_section": {"width": 0.01, "height": 0.007}},
  "supports": [{"vertex": 0, "fix": ["position"]}, {"vertex": 1, "fix": ["y", "z"]}],
  "solver": {"gradient_tolerance": 1e-12}, "output": {"directory": "out", "solids": false})" +
         extra + "}";
}

void write_lath(const fs::path& dir) { write_text(dir / "lath.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"); }

}  // namespace

TEST_CASE("rest_lengths: a free lath relaxes to its given rest length, and is cut to it") {
  const ScratchDirectory scratch("rest-lengths-lath");
  const fs::path& dir = scratch.path();
  write_lath(dir);
  write_text(dir / "run.json", lath_config(R"(, "rest_lengths": [1.02])"));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["converged"] == true);
  CHECK(s["configuration"]["rest_lengths"] == nlohmann::json({1.02}));
  // Unloaded: the free end lies at the rest length, unstrained.
  CHECK(std::abs(s["vertices"][1][0].get<double>() - 1.02) <= 1e-9);
  CHECK(std::abs(s["vertices"][1][1].get<double>()) <= 1e-12);
  CHECK(s["energy"]["stretching"].get<double>() <= 1e-20);
  // It started as drawn, compressed by 1/1.02 - 1: E = EA/2 (1/1.02 - 1)^2 1.02.
  const double ea = 2e4 * 0.01 * 0.007, strain = 1 / 1.02 - 1;
  CHECK(s["history"][0]["energy"].get<double>() ==
        doctest::Approx(0.5 * ea * strain * strain * 1.02).epsilon(1e-12));

  // The lath is cut 1.02 long; 1 without the key.
  REQUIRE(run_xshell("fabricate run.json --out cut", dir).status == 0);
  const nlohmann::json cut = read_json(dir / "cut" / "fabrication.json");
  CHECK(cut["rods"][0]["length"].get<double>() == doctest::Approx(1.02).epsilon(1e-14));
  write_text(dir / "drawn.json", lath_config(""));
  REQUIRE(run_xshell("fabricate drawn.json --out drawn", dir).status == 0);
  CHECK(read_json(dir / "drawn" / "fabrication.json")["rods"][0]["length"].get<double>() ==
        doctest::Approx(1.0).epsilon(1e-14));
}

TEST_CASE("rest_lengths: the lath's weight follows its rest length") {
  const ScratchDirectory scratch("rest-lengths-weight");
  const fs::path& dir = scratch.path();
  write_lath(dir);
  std::string config =
      lath_config(R"(, "rest_lengths": [1.02], "loads": {"gravity": [0, 0, -10]})");
  config.replace(config.find("\"young_modulus\""), 0, "\"density\": 1000, ");
  // The sagging lath converges to a gradient of 1.7e-11 (round-off).
  config.replace(config.find("1e-12"), 5, "1e-10");
  write_text(dir / "run.json", config);
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  double lifted = 0.0;
  for (const nlohmann::json& reaction : s["reactions"])
    lifted += reaction["force"][2].get<double>();
  CHECK(lifted == doctest::Approx(1000 * 0.01 * 0.007 * 10 * 1.02).epsilon(1e-12));
}

TEST_CASE("rest_lengths: --init takes a state of the same rest lengths, refuses one of others") {
  const ScratchDirectory scratch("rest-lengths-init");
  const fs::path& dir = scratch.path();
  write_lath(dir);
  write_text(dir / "run.json", lath_config(R"(, "rest_lengths": [1.02])"));
  write_text(dir / "other.json", lath_config(R"(, "rest_lengths": [1.03])"));
  write_text(dir / "drawn.json", lath_config(""));
  REQUIRE(run_xshell("relax run.json", dir).status == 0);
  REQUIRE(run_xshell("relax drawn.json --out drawn", dir).status == 0);
  CommandResult r = run_xshell("relax run.json --init out/state.json --out again", dir);
  CAPTURE(r.errors);
  CHECK(r.status == 0);
  CHECK(read_json(dir / "again" / "summary.json")["iterations"] == 0);  // already at rest
  r = run_xshell("relax other.json --init out/state.json --out other", dir);
  CHECK(r.status == 2);
  CHECK(r.errors.find("out/state.json: the state was saved with other \"rest_lengths\" (segment "
                      "0: 1.02 in the state, 1.03 in this run)") != std::string::npos);
  r = run_xshell("relax drawn.json --init out/state.json --out drawn2", dir);
  CHECK(r.status == 2);
  CHECK(r.errors.find("this run has the drawing's rest lengths") != std::string::npos);
  // A state of the drawing's lengths (as every state before the key) restores
  // into a run without the key, and is refused by one with it.
  CHECK(run_xshell("relax drawn.json --init drawn/state.json --out drawn3", dir).status == 0);
  r = run_xshell("relax run.json --init drawn/state.json --out mixed", dir);
  CHECK(r.status == 2);
  CHECK(r.errors.find("saved with the drawing's rest lengths, this run gives") !=
        std::string::npos);
}

TEST_CASE("rest_lengths: a wrong count or bad values exit with status 2 naming the key") {
  const ScratchDirectory scratch("rest-lengths-bad");
  const fs::path& dir = scratch.path();
  write_lath(dir);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[1.0, 1.0]",
       "run.json: rest_lengths: 2 rest lengths given; the linkage has 1 segment, so it needs 1"},
      {"[0]", "run.json: rest_lengths[0]: must be > 0, got 0"},
      {"[-1.5]", "run.json: rest_lengths[0]: must be > 0, got -1.5"},
      {"[1e400]", "rest_lengths[0]"},
      {"[\"1\"]", "run.json: rest_lengths[0]: expected a number"},
      {"1.02", "run.json: rest_lengths: expected an array"},
      {"[]", "run.json: rest_lengths: must list one rest length per segment"}};
  for (const auto& [value, message] : cases) {
    CAPTURE(value);
    write_text(dir / "run.json", lath_config(", \"rest_lengths\": " + value));
    for (const char* command : {"relax", "fabricate"}) {
      CAPTURE(command);
      const CommandResult r = run_xshell(std::string(command) + " run.json", dir);
      CAPTURE(r.errors);
      CHECK(r.status == 2);
      CHECK(r.errors.find(message) != std::string::npos);
    }
  }
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("rest_lengths: a deployment of the grid with lengthened x laths completes at them") {
  // The sample grid (40 segments, a flat 4 x 4 grid of straight laths) with
  // every segment along x 3% longer: still a grid, stress-free, so every
  // segment measures its rest length joint to joint at every step.
  const fs::path obj = fs::path(XSHELL_SAMPLES_DIR) / "grid.obj";
  const LineGraph graph = read_obj(obj.string());
  nlohmann::json lengths = nlohmann::json::array();
  for (const auto& [a, b] : graph.edges) {
    const Eigen::Vector3d d = graph.vertices[b] - graph.vertices[a];
    lengths.push_back(d.norm() * (d.y() == 0.0 ? 1.03 : 1.0));
  }
  const ScratchDirectory scratch("rest-lengths-deploy");
  const fs::path& dir = scratch.path();
  nlohmann::json config = {
      {"linkage", obj.string()},
      {"subdivisions", 4},
      {"rest_shape", "straight"},
      {"rest_lengths", lengths},
      {"material",
       {{"young_modulus", 2e10}, {"cross_section", {{"width", 0.01}, {"height", 0.007}}}}},
      {"supports", {{{"vertex", 12}, {"fix", {"position", "orientation"}}}}},
      {"deployment", {{"average_opening_angle", 1.3}, {"steps", 2}}},
      {"output", {{"directory", "out"}, {"solids", false}}}};
  write_text(dir / "run.json", config.dump());
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["deployment"]["status"] == "completed");
  CHECK(s["deployment"]["final_average_angle"].get<double>() ==
        doctest::Approx(1.3).epsilon(1e-12));
  double worst = 0.0;
  for (std::size_t e = 0; e < graph.edges.size(); ++e) {
    const auto& [a, b] = graph.edges[e];
    Eigen::Vector3d d;
    for (int c = 0; c < 3; ++c)
      d[c] = s["vertices"][b][c].get<double>() - s["vertices"][a][c].get<double>();
    worst = std::max(worst, std::abs(d.norm() - lengths[e].get<double>()));
  }
  CHECK(worst <= 1e-9);
}

}  // namespace xshell::test
