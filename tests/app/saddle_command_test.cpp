// `xshell relax` at a saddle: a clamped-free column beyond Euler's load,
// exactly straight. By default the run leaves the saddle on the side of
// solver.buckling_direction and says so in summary.json ("saddles_escaped");
// "escape_saddles": false reports the saddle itself.
#include <doctest/doctest.h>

#include <cmath>

#include "command_runner.hpp"

namespace xshell::test {

namespace {

// Length 1 along x, clamped at vertex 0, the axial load 1.2 P_cr at vertex
// 1; rectangle 0.01 x 0.012 with the weak E I = 1 (P_cr = pi^2 / 4).
std::string column_config(const nlohmann::json& solver) {
  nlohmann::json c = {
      {"linkage", "column.obj"},
      {"subdivisions", 30},
      {"rest_shape", "straight"},
      {"material",
       {{"young_modulus", 1e9},
        {"density", 1000},
        {"cross_section", {{"shape", "rectangle"}, {"width", 0.01}, {"height", 0.012}}}}},
      {"supports", {{{"vertex", 0}, {"fix", {"position", "orientation"}}}}},
      {"loads", {{"forces", {{{"vertex", 1}, {"force", {-1.2 * M_PI * M_PI / 4.0, 0, 0}}}}}}},
      {"solver", solver},
      {"output", {{"directory", "out"}, {"solids", false}}}};
  return c.dump(2);
}

}  // namespace

TEST_CASE("relax: a saddle is left on the chosen side and listed, or kept on request") {
  const ScratchDirectory scratch("saddle");
  const fs::path& dir = scratch.path();
  write_text(dir / "column.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  int checked = 0;
  for (double side : {1.0, -1.0}) {
    CAPTURE(side);
    write_text(dir / "run.json", column_config({{"gradient_tolerance", 1e-9},
                                                {"max_iterations", 200},
                                                {"buckling_direction", {0, side, side}}}));
    const CommandResult r = run_xshell("relax run.json", dir);
    CAPTURE(r.errors);
    REQUIRE(r.status == 0);
    const nlohmann::json s = read_json(dir / "out" / "summary.json");
    CHECK(s["stable"] == true);
    REQUIRE(s["saddles_escaped"].size() == 1);
    const nlohmann::json& saddle = s["saddles_escaped"][0];
    CHECK(saddle["lowest_eigenvalue"].get<double>() < 0.0);
    CHECK(saddle["energy"].get<double>() > s["energy"]["total"].get<double>());
    CHECK(saddle["step"].is_null());
    const double y = s["vertices"][1][1], z = s["vertices"][1][2];
    CHECK(side * (y + z) > 0.1);  // buckled (the elastica: 0.47 sideways), on the chosen side
    CHECK(s["configuration"]["solver"]["buckling_direction"] == nlohmann::json({0.0, side, side}));
    ++checked;
  }
  write_text(dir / "run.json",
             column_config({{"gradient_tolerance", 1e-9}, {"escape_saddles", false}}));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["stable"] == false);
  CHECK(s["saddles_escaped"] == nlohmann::json::array());
  CHECK(std::hypot(s["vertices"][1][1].get<double>(), s["vertices"][1][2].get<double>()) < 1e-9);
  CHECK(s["configuration"]["solver"]["escape_saddles"] == false);
  CHECK(checked == 2);
}

}  // namespace xshell::test
