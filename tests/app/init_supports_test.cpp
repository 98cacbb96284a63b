// Supports of a run that starts from a saved state (--init): a support
// holds input + displacement (as without --init), so one whose vertex the
// state has elsewhere starts far from where it is held. That is warned of
// (stderr and the summary's warnings, with the displacement that would hold
// it where it starts), and a failed solve's reason names it.
#include <doctest/doctest.h>

#include <sstream>

#include "reliability_support.hpp"

namespace xshell::test::init_supports_test {

namespace {

// The grid held at its centre (vertex 4) and by `supports`; `solver` and
// `top` are extra keys of "solver" and of the configuration.
std::string grid_config(const std::string& supports, const std::string& solver = "",
                        const std::string& top = "") {
  return R"({
  "linkage": "grid.obj",
  "subdivisions": 5,
  "rest_shape": "input",
  "material": {"young_modulus": 2.0e10, "cross_section": {"shape": "rectangle", "width": 0.01, "height": 0.007}},
  "supports": [{"vertex": 4, "fix": ["position", "orientation"]})" +
         supports + R"(],
  "solver": {"gradient_tolerance": 1e-9)" +
         solver + "}" + top + R"(,
  "output": {"directory": "out", "solids": false}
})";
}

// The grid opened from pi/2 to an average angle of 2.0 rad into opened/:
// its corners move away from the input.
void write_opened_state(const ScratchDirectory& dir) {
  write_text(dir / "grid.obj", flat_grid_obj());
  write_text(dir / "open.json", grid_config("", "", R"(,
  "deployment": {"average_opening_angle": 2.0, "steps": 4})"));
  const CommandResult r = run_xshell("relax open.json --out opened", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
}

// The [x, y, z] after `"displacement": ` in `text`.
std::string suggested_displacement(const std::string& text) {
  const std::string key = "\"displacement\": ";
  const size_t at = text.find(key);
  REQUIRE(at != std::string::npos);
  const size_t end = text.find(']', at);
  REQUIRE(end != std::string::npos);
  return text.substr(at + key.size(), end + 1 - at - key.size());
}

}  // namespace

TEST_CASE("relax --init: supports hold input + displacement and a moved one is warned of") {
  const ScratchDirectory dir("init-supports");
  write_opened_state(dir);
  const nlohmann::json opened = read_json(dir / "opened" / "summary.json");
  const std::string corners = R"(, {"vertex": 0, "fix": ["position"], "displacement": [0, 0, 1e-6]},
    {"vertex": 8, "fix": ["position"]})";
  write_text(dir / "pinned.json", grid_config(corners));
  const CommandResult r = run_xshell("relax pinned.json --init opened/state.json", dir.path());
  CAPTURE(r.errors);
  CHECK(contains(r.errors, "xshell: warning: supports[1] (vertex 0) starts "));
  CHECK(contains(r.errors, "xshell: warning: supports[2] (vertex 8) starts "));
  CHECK(contains(r.errors, "from where it is held (input + displacement"));
  CHECK_FALSE(contains(r.errors, "supports[0]"));  // the centre did not move
  REQUIRE(fs::exists(dir / "out" / "summary.json"));
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  REQUIRE(s["warnings"].size() == 2);
  CHECK(contains(s["warnings"][0].get<std::string>(), "supports[1] (vertex 0)"));
  CHECK(contains(s["warnings"][1].get<std::string>(), "supports[2] (vertex 8)"));
  // Held at input + displacement, not at the state's position + displacement.
  CHECK(s["vertices"][0][0].get<double>() == 0.0);
  CHECK(s["vertices"][0][1].get<double>() == 0.0);
  CHECK(s["vertices"][0][2].get<double>() == 1e-6);
  CHECK(s["vertices"][8][0].get<double>() == 0.5);
  CHECK(s["vertices"][8][1].get<double>() == 0.5);

  // The displacement the warning suggests holds the corners where the state
  // has them: no warning, and the state is already the equilibrium.
  const std::string d0 = suggested_displacement(s["warnings"][0].get<std::string>());
  const std::string d8 = suggested_displacement(s["warnings"][1].get<std::string>());
  write_text(dir / "kept.json",
             grid_config(R"(, {"vertex": 0, "fix": ["position"], "displacement": )" + d0 +
                         R"(}, {"vertex": 8, "fix": ["position"], "displacement": )" + d8 + "}"));
  const CommandResult kept =
      run_xshell("relax kept.json --init opened/state.json --out kept", dir.path());
  CAPTURE(kept.errors);
  REQUIRE(kept.status == 0);
  CHECK_FALSE(contains(kept.errors, "warning"));
  const nlohmann::json k = read_json(dir / "kept" / "summary.json");
  CHECK(k["warnings"] == nlohmann::json::array());
  for (int v : {0, 8})
    for (int c = 0; c < 3; ++c)
      CHECK(k["vertices"][v][c].get<double>() ==
            doctest::Approx(opened["vertices"][v][c].get<double>()).epsilon(1e-8).scale(1e-8));
}

TEST_CASE("relax --init: a failed solve's reason names the support that started far away") {
  const ScratchDirectory dir("init-supports-failed");
  write_opened_state(dir);
  write_text(dir / "pinned.json",
             grid_config(R"(, {"vertex": 0, "fix": ["position"]})", R"(, "max_iterations": 1)"));
  const CommandResult r = run_xshell("relax pinned.json --init opened/state.json", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 3);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  const std::string reason = s["reason"].get<std::string>();
  CAPTURE(reason);
  CHECK(reason.rfind("supports[1] (vertex 0) started ", 0) == 0);
  CHECK(contains(last_line(r.errors), "supports[1] (vertex 0) started "));
}

TEST_CASE("relax: a small displacement without --init is not warned of") {
  const ScratchDirectory dir("init-supports-none");
  write_text(dir / "grid.obj", flat_grid_obj());
  write_text(dir / "run.json",
             grid_config(R"(, {"vertex": 0, "fix": ["position"], "displacement": [0, 0, 1e-3]})"));
  const CommandResult r = run_xshell("relax run.json", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  CHECK_FALSE(contains(r.errors, "warning"));
  CHECK(read_json(dir / "out" / "summary.json")["warnings"] == nlohmann::json::array());
  // A displacement of a tenth of the span, applied in one jump, is.
  write_text(dir / "far.json",
             grid_config(R"(, {"vertex": 0, "fix": ["position"], "displacement": [0, 0, 0.05]})"));
  const CommandResult far = run_xshell("relax far.json --out far", dir.path());
  CAPTURE(far.errors);
  CHECK(contains(far.errors, "xshell: warning: supports[1] (vertex 0) starts 0.05 from where"));
  CHECK_FALSE(contains(far.errors, "--init"));
}

TEST_CASE("relax --init: a deployment with edge-vector joints names the joints, not the state") {
  // A state whose centre joint is closed to zero: its rods are parallel
  // there, which edge-vector joints cannot express. The deployment, which
  // needs rotation joints anyway, is what to report.
  const ScratchDirectory dir("init-edge-vectors");
  write_text(dir / "grid.obj", flat_grid_obj());
  write_text(dir / "run.json", grid_config(""));
  REQUIRE(run_xshell("relax run.json --out relaxed", dir.path()).status == 0);
  nlohmann::json state = read_json(dir / "relaxed" / "state.json");
  for (nlohmann::json& joint : state["joints"])
    if (joint["vertex"] == 4) joint["params"][6] = 0.0;  // alpha
  write_text(dir / "closed.json", state.dump());
  std::string config = grid_config("", "", R"(,
  "deployment": {"average_opening_angle": 0.5, "steps": 2})");
  config.insert(config.find('{') + 1, R"("joints": "edge_vectors",)");
  write_text(dir / "edges.json", config);
  const CommandResult r = run_xshell("relax edges.json --init closed.json", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 2);
  CHECK(contains(r.errors, "deployment: needs \"joints\": \"rotation\""));
  CHECK_FALSE(contains(r.errors, "state"));
}

}  // namespace xshell::test::init_supports_test
