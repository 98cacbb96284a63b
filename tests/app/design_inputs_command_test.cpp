// The command with a transform, a support selector and a line load: what the
// summary and the fabrication data say about them (README, "Transforms",
// "Support selectors", loads.line_loads).
#include <doctest/doctest.h>

#include "command_runner.hpp"

namespace xshell::test {

TEST_CASE("relax: a transformed sample held on its boundary under a line load") {
  const ScratchDirectory scratch("design-inputs");
  const fs::path& dir = scratch.path();
  write_text(dir / "run.json", R"({
  "linkage": ")" + (fs::path(XSHELL_SAMPLES_DIR) / "grid.obj").string() +
                                   R"(",
  "transform": {"scale": 2, "rotate_deg": [0, 0, 90], "translate": [0, 0, 1]},
  "subdivisions": 5,
  "rest_shape": "straight",
  "material": {"young_modulus": 2.0e10,
               "cross_section": {"shape": "rectangle", "width": 0.01, "height": 0.007}},
  "supports": [{"select": "boundary", "fix": ["position"]}],
  "loads": {"line_loads": [{"rods": "all", "force_per_length": [0, 0, -2.0]}]},
  "output": {"directory": "out"}
})");
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["converged"] == true);
  // Every vertex but the four inner joints (12, 13, 17, 21): the 12 joints of
  // the outer ring and the 16 free ends.
  std::vector<int> boundary;
  for (int v = 0; v < 32; ++v)
    if (v != 12 && v != 13 && v != 17 && v != 21) boundary.push_back(v);
  REQUIRE(s["supports"].size() == 1);
  CHECK(s["supports"][0]["entry"] == 0);
  CHECK(s["supports"][0]["vertices"].get<std::vector<int>>() == boundary);
  // The held vertices stay at their transformed input positions: vertex 0,
  // (-0.5, -0.375, 0) in the file, scaled by 2, turned 90 degrees about z,
  // raised by 1.
  const nlohmann::json& v0 = s["vertices"][0];
  CHECK(v0[0].get<double>() == doctest::Approx(0.75));
  CHECK(v0[1].get<double>() == doctest::Approx(-1.0));
  CHECK(v0[2].get<double>() == doctest::Approx(1.0));
  // The inner joints sag under the line load.
  for (int v : {12, 13, 17, 21}) CHECK(s["vertices"][v][2].get<double>() < 1.0 - 1e-4);
  // The applied transform, with its matrix.
  const nlohmann::json& t = s["transform"];
  CHECK(t["scale"] == 2.0);
  CHECK(t["mirror"].is_null());
  CHECK(t["matrix"][0][1].get<double>() == doctest::Approx(-2.0));
  CHECK(t["matrix"][1][0].get<double>() == doctest::Approx(2.0));
  CHECK(t["matrix"][2][3].get<double>() == 1.0);
  CHECK(s["configuration"]["loads"]["line_loads"][0]["rods"] == "all");
  // The fabrication data are in the scaled unit, and say so.
  const nlohmann::json fab = read_json(dir / "out" / "fabrication.json");
  const std::string unit = fab["units"]["length"];
  CHECK(unit.find("grid.obj x 2") != std::string::npos);
  CHECK(fab["rods"][0]["length"].get<double>() > 1.9);  // the file's rods are 1 long
}

TEST_CASE(
    "relax --init: a support far from where it is held is named by its entry of \"supports\"") {
  // The first run lets the middle of the grid sag under a line load; the
  // second starts there and holds two of the sagged joints at the input. The
  // model has one support per selected vertex: the warning and the reason
  // name the configuration's entry, supports[1], not the model's sixth.
  const ScratchDirectory scratch("far-selected");
  const fs::path& dir = scratch.path();
  const std::string corners = R"({"select": [1, 4, 9, 28], "fix": ["position"]})";
  const std::string load =
      R"("loads": {"line_loads": [{"rods": "all", "force_per_length": [0, 0, -40]}]})";
  write_text(dir / "sag.json", R"({
  "linkage": ")" + (fs::path(XSHELL_SAMPLES_DIR) / "grid.obj").string() +
                                   R"(",
  "subdivisions": 5, "rest_shape": "straight",
  "material": {"young_modulus": 2.0e10,
               "cross_section": {"shape": "rectangle", "width": 0.01, "height": 0.007}},
  "supports": [)" + corners + R"(], )" +
                                   load + R"(, "output": {"directory": "sag"}})");
  const CommandResult first = run_xshell("relax sag.json", dir);
  CAPTURE(first.errors);
  REQUIRE(first.status == 0);
  const double sag = read_json(dir / "sag" / "summary.json")["vertices"][12][2].get<double>();
  REQUIRE(sag < -0.016);  // more than 1% of the 1.41 m diagonal
  std::string held = read_text(dir / "sag.json");
  held.replace(held.find(corners), corners.size(),
               corners + R"(, {"select": [12, 13], "fix": ["position"]})");
  held.replace(held.find(R"("directory": "sag")"), 18, R"("directory": "held")");
  write_text(dir / "held.json", held);
  const CommandResult second = run_xshell("relax held.json --init sag/state.json", dir);
  CAPTURE(second.errors);
  CHECK(second.errors.find("supports[1] (vertex 12) starts") != std::string::npos);
  CHECK(second.errors.find("supports[5]") == std::string::npos);
}

}  // namespace xshell::test
