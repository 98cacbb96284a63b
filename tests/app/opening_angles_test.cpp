// Opening angles in the outputs of `xshell relax`: their range in the
// summary and in deployment.csv, and the warning (stderr and the summary)
// when a joint's angle leaves (0, pi), where the rods have passed through
// each other.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reliability_support.hpp"
#include "skip.hpp"

namespace xshell::test::opening_angles_test {

namespace {

std::string grid_config(const std::string& deployment) {
  return R"({
  "linkage": "grid.obj",
  "subdivisions": 5,
  "rest_shape": "input",
  "material": {"young_modulus": 2.0e10, "cross_section": {"shape": "rectangle", "width": 0.01, "height": 0.007}},
  "supports": [{"vertex": 4, "fix": ["position", "orientation"]}],
  "solver": {"gradient_tolerance": 1e-9})" +
         (deployment.empty() ? "" : ",\n  \"deployment\": " + deployment) + R"(,
  "output": {"directory": "out", "solids": false}
})";
}

// A state of the grid whose centre joint (vertex 4) is closed through zero
// to -0.1 rad, as a run that drove it there would leave it: the relaxed
// grid's state with that joint's alpha changed.
void write_closed_state(const ScratchDirectory& dir) {
  write_text(dir / "grid.obj", flat_grid_obj());
  write_text(dir / "run.json", grid_config(""));
  const CommandResult r = run_xshell("relax run.json --out relaxed", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  nlohmann::json state = read_json(dir / "relaxed" / "state.json");
  int changed = 0;
  for (nlohmann::json& joint : state["joints"])
    if (joint["vertex"] == 4) {
      joint["params"][6] = -0.1;  // p, omega, alpha, l_A, l_B
      ++changed;
    }
  REQUIRE(changed == 1);
  write_text(dir / "closed.json", state.dump());
}

}  // namespace

TEST_CASE("relax: the summary gives the range of the opening angles, no warning inside (0, pi)") {
  const ScratchDirectory dir("angles-inside");
  write_text(dir / "grid.obj", flat_grid_obj());
  write_text(dir / "run.json", grid_config(""));
  const CommandResult r = run_xshell("relax run.json", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  REQUIRE(s["min_opening_angle"].is_number());
  CHECK(s["min_opening_angle"].get<double>() == doctest::Approx(M_PI / 2).epsilon(1e-9));
  CHECK(s["max_opening_angle"].get<double>() == doctest::Approx(M_PI / 2).epsilon(1e-9));
  CHECK(s["joints_outside_opening_range"] == nlohmann::json::array());
  CHECK(s["warnings"] == nlohmann::json::array());
  CHECK_FALSE(contains(r.errors, "warning"));
}

TEST_CASE("relax: a joint closed through zero is warned of and listed in the summary") {
  const ScratchDirectory dir("angles-outside");
  write_closed_state(dir);
  // The closed joint's angle held where the state has it.
  std::string held = grid_config("");
  held.replace(held.find(R"(["position", "orientation"])"), 27,
               R"(["position", "orientation", "opening_angle"])");
  write_text(dir / "held.json", held);
  const CommandResult r = run_xshell("relax held.json --init closed.json", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  // The flat grid of straight rods is a mechanism: every joint follows the
  // centre through zero, at no cost in energy.
  CHECK(contains(r.errors, "xshell: warning: 9 joints have their opening angle outside (0, pi)"));
  CHECK(contains(r.errors, "vertex 4 at -0.1 rad"));
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["min_opening_angle"].get<double>() == doctest::Approx(-0.1).epsilon(1e-9));
  CHECK(s["max_opening_angle"].get<double>() == doctest::Approx(-0.1).epsilon(1e-6));
  const nlohmann::json& outside = s["joints_outside_opening_range"];
  REQUIRE(outside.size() == 9);
  for (int k = 0; k < 9; ++k) {
    CHECK(outside[k]["vertex"] == k);
    CHECK(outside[k]["angle"].get<double>() == doctest::Approx(-0.1).epsilon(1e-6));
    CHECK(outside[k]["angle"] == s["opening_angles"][k]);
  }
  REQUIRE(s["warnings"].size() == 1);
  CHECK(contains(s["warnings"][0].get<std::string>(), "outside (0, pi)"));
}

TEST_CASE("relax: deployment.csv gives each step's smallest and largest opening angle") {
  const ScratchDirectory dir("angles-deployment");
  write_closed_state(dir);
  // Opened back from -0.1 rad to 0.5 rad at the centre: step 0 (the start,
  // every joint at -0.1 rad) is outside (0, pi) and warned of, the end is
  // inside.
  write_text(dir / "open.json",
             grid_config(R"({"joint_angles": [{"vertex": 4, "angle": 0.5}], "steps": 2})"));
  const CommandResult r = run_xshell("relax open.json --init closed.json", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  CHECK(contains(r.errors, "xshell: warning: deployment step 0: 9 joints outside (0, pi)"));
  CHECK_FALSE(contains(r.errors, "joint has its opening angle outside"));
  std::istringstream table(read_text(dir / "out" / "deployment.csv"));
  std::string header;
  std::getline(table, header);
  CHECK(header ==
        "step,average_angle,energy_total,energy_stretching,energy_bending,energy_twisting,torque,"
        "iterations,stable,min_opening_angle,max_opening_angle,factorizations");
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(table, line);) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  REQUIRE(rows.size() == 3);
  for (const auto& row : rows) REQUIRE(row.size() == 12);
  CHECK(std::stod(rows[0][9]) == doctest::Approx(-0.1).epsilon(1e-9));
  CHECK(std::stod(rows[2][9]) > 0.0);
  CHECK(std::stod(rows[2][10]) < M_PI);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(std::stod(rows[2][9]) == s["min_opening_angle"].get<double>());
  CHECK(std::stod(rows[2][10]) == s["max_opening_angle"].get<double>());
  CHECK(s["joints_outside_opening_range"] == nlohmann::json::array());
  // The step's warning, once, in the summary too.
  REQUIRE(s["warnings"].size() == 1);
  CHECK(s["warnings"][0].get<std::string>().rfind("deployment step 0: 9 joints outside (0, pi)",
                                                  0) == 0);
}

TEST_CASE("Manta ray relaxed flat: its smallest opening angle and the joints through zero" *
          doctest::test_suite("validation")) {
  const fs::path obj = fs::path(XSHELL_SHARED_DATA_DIR) / "manta_ray_5ca2f7ab.obj";
  if (!fs::exists(obj)) XSHELL_SKIP(obj.string() + " is absent");
  const ScratchDirectory dir("angles-manta");
  // The designs' laths (mm, 10 x 7, E = 20000 MPa), straight at rest,
  // relaxed from the flat input under the default pin.
  const std::string config = R"({
  "linkage": ")" + obj.string() +
                             R"(",
  "subdivisions": 8,
  "rest_shape": "straight",
  "material": {"young_modulus": 20000, "cross_section": {"shape": "rectangle", "width": 10, "height": 7}},
  "output": {"directory": "flat", "solids": false}
})";
  write_text(dir / "flat.json", config);
  const CommandResult r = run_xshell("relax flat.json", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "flat" / "summary.json");
  // The summary's range and list agree with its opening angles.
  double lo = 10.0, hi = -10.0;
  std::vector<int> outside;
  for (int v = 0; v < static_cast<int>(s["opening_angles"].size()); ++v) {
    if (s["opening_angles"][v].is_null()) continue;
    const double a = s["opening_angles"][v].get<double>();
    lo = std::min(lo, a);
    hi = std::max(hi, a);
    if (!(a > 0.0 && a < M_PI)) outside.push_back(v);
  }
  CHECK(s["min_opening_angle"].get<double>() == lo);
  CHECK(s["max_opening_angle"].get<double>() == hi);
  REQUIRE(s["joints_outside_opening_range"].size() == outside.size());
  for (size_t k = 0; k < outside.size(); ++k)
    CHECK(s["joints_outside_opening_range"][k]["vertex"] == outside[k]);
  MESSAGE("manta ray relaxed flat: opening angles " << lo << " to " << hi << " rad, "
                                                    << outside.size() << " outside (0, pi)");
  // The case this test shows: relaxed flat, a nearly collinear valence-2
  // joint already closes through zero (-0.016 rad at vertex 36 when
  // written), and the run says so.
  CHECK(lo < 0.0);
  CHECK(!outside.empty());
  CHECK(contains(r.errors, "xshell: warning: " + std::to_string(outside.size()) + " joint"));
  CHECK(contains(r.errors, "outside (0, pi)"));
  CHECK(s["warnings"].size() == 1);

  // Closed further (average 0.15 rad): more joints pass through zero, each
  // deployment step's range is in deployment.csv, the last one the summary's.
  std::string close = config;
  close.replace(close.find(R"("output")"), 0,
                R"("deployment": {"average_opening_angle": 0.15, "steps": 5},
  )");
  close.replace(close.find(R"("flat")"), 6, R"("closed")");
  write_text(dir / "close.json", close);
  const CommandResult c = run_xshell("relax close.json --init flat/state.json", dir.path());
  CAPTURE(c.errors);
  REQUIRE(c.status == 0);
  const nlohmann::json closed = read_json(dir / "closed" / "summary.json");
  const size_t closed_outside = closed["joints_outside_opening_range"].size();
  MESSAGE("closed to 0.15 rad: smallest opening angle "
          << closed["min_opening_angle"].get<double>() << " rad, " << closed_outside
          << " joints outside (0, pi), stable " << closed["stable"]);
  CHECK(closed_outside > outside.size());
  CHECK(contains(c.errors, "xshell: warning: deployment step 0: "));
  CHECK(contains(c.errors, "xshell: warning: " + std::to_string(closed_outside) + " joints"));
  CHECK(closed["warnings"].size() == 2);  // the deployment's and the final state's
  std::istringstream table(read_text(dir / "closed" / "deployment.csv"));
  std::string line, last;
  while (std::getline(table, line))
    if (!line.empty()) last = line;
  std::vector<std::string> cells;
  std::istringstream row(last);
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
  REQUIRE(cells.size() == 12);
  CHECK(std::stod(cells[9]) == closed["min_opening_angle"].get<double>());
}

}  // namespace xshell::test::opening_angles_test
