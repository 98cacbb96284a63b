// The command with a transform, a support selector and a line load: what the
// summary and the fabrication data say about them (README, "Transforms",
// "Support selectors", loads.line_loads).
#include <doctest/doctest.h>

#include "command_runner.hpp"

namespace xshell::test {

TEST_CASE("relax: a transformed sample held on its boundary under a line load") {
  const fs::path dir = temporary_directory("design-inputs");
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

}  // namespace xshell::test
