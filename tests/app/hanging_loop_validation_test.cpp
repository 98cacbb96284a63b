// Validation on a real graph (../shared/data/elasticrods; skipped when
// absent): fish_linkage, a loop of four joints with two free ends, one of
// them clamped, sagging under its own weight, relaxed by Newton from flat in few
// iterations (the mixed Hessian, docs/model.md section 9.8).
#include <doctest/doctest.h>

#include "command_runner.hpp"
#include "skip.hpp"

namespace xshell::test {

TEST_CASE("fish_linkage under gravity: relaxed from flat in at most 40 Newton iterations" *
          doctest::test_suite("validation")) {
  const fs::path data = XSHELL_SHARED_DATA_DIR;
  if (!fs::is_directory(data)) XSHELL_SKIP(data.string() + " is absent");
  const ScratchDirectory scratch("fish_hanging");
  const fs::path& dir = scratch.path();
  const nlohmann::json config = {
      {"linkage", (data / "fish_linkage.obj").string()},
      {"subdivisions", 8},
      {"material",
       {{"young_modulus", 2e9},
        {"density", 1000},
        {"cross_section", {{"shape", "rectangle"}, {"width", 0.02}, {"height", 0.01}}}}},
      {"supports", {{{"vertex", 0}, {"fix", {"position", "orientation"}}}}},
      {"loads", {{"gravity", {0, 0, -9.81}}}},
      {"solver", {{"max_iterations", 500}}},
      {"output", {{"directory", "out"}, {"every", 100000}}}};
  write_text(dir / "run.json", config.dump(2));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json summary = read_json(dir / "out" / "summary.json");
  CHECK(summary["converged"] == true);
  CHECK(summary["stable"] == true);
  const int iterations = summary["iterations"].get<int>();
  MESSAGE("fish_linkage under gravity: " << iterations << " Newton iterations");
  CHECK(iterations <= 40);
  // It sags: the loop's far joint (vertex 5, 0.47 m from the clamp) by millimetres.
  const nlohmann::json& vertices = summary["vertices"];
  REQUIRE(vertices.size() == 6);
  CHECK(vertices[5][2].get<double>() < vertices[0][2].get<double>() - 0.005);
}

}  // namespace xshell::test
