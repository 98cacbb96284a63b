// `xshell fabricate` (app/fabricate_command.hpp), run directly: the files
// from a configuration's linkage as drawn and from a relaxed state, and the
// exit statuses of bad input and unwritable output.
#include "app/fabricate_command.hpp"

#include <doctest/doctest.h>

#include "app/exit_status.hpp"
#include "command_runner.hpp"

namespace xshell::test {

TEST_CASE("fabricate: the configuration's linkage as drawn") {
  const ScratchDirectory scratch("fabricate");
  const fs::path& dir = scratch.path();
  write_text(dir / "run.json", sample_config(dir / "out"));
  FabricateArguments args;
  args.config = (dir / "run.json").string();
  REQUIRE(run_fabricate(args) == kExitConverged);
  for (const char* name : {"fabrication.json", "fabrication.csv", "fabrication.svg"})
    CHECK(fs::exists(dir / "out" / name));
  const nlohmann::json f = read_json(dir / "out" / "fabrication.json");
  CHECK(f["units"]["length"] == "length unit of grid.obj");
  CHECK(f["units"]["angle"] == "radian");
  REQUIRE(f["rods"].size() == 8);
  REQUIRE(f["joints"].size() == 16);
  for (const auto& rod : f["rods"]) {
    CHECK(rod["length"].get<double>() == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(rod["cross_section"]["width"].get<double>() == 0.01);
    CHECK(rod["cross_section"]["height"].get<double>() == 0.007);
  }
  // As drawn: the current angles are the input's.
  for (const auto& joint : f["joints"])
    CHECK(joint["angle"].get<double>() ==
          doctest::Approx(joint["angle_input"].get<double>()).epsilon(1e-12));
  // Nothing but the fabrication files: no solve, no VTK series.
  CHECK(!fs::exists(dir / "out" / "summary.json"));
  CHECK(!fs::exists(dir / "out" / "series.pvd"));
  fs::remove_all(dir);
}

TEST_CASE("fabricate --init: the angles of a relaxed state and the lengths of the rest state") {
  const ScratchDirectory scratch("fabricate-init");
  const fs::path& dir = scratch.path();
  write_text(dir / "run.json", sample_config(dir / "relaxed"));
  const CommandResult relax = run_xshell("relax run.json --quiet", dir);
  CAPTURE(relax.errors);
  REQUIRE(relax.status == 0);
  FabricateArguments args;
  args.config = (dir / "run.json").string();
  args.init = (dir / "relaxed" / "state.json").string();
  args.out = (dir / "fab").string();
  REQUIRE(run_fabricate(args) == kExitConverged);
  const nlohmann::json f = read_json(dir / "fab" / "fabrication.json");
  const nlohmann::json s = read_json(dir / "relaxed" / "summary.json");
  int moved = 0, checked = 0;
  for (const auto& joint : f["joints"]) {
    const int v = joint["vertex"].get<int>();
    CHECK(joint["angle"].get<double>() ==
          doctest::Approx(s["opening_angles"][v].get<double>()).epsilon(1e-12));
    moved += std::abs(joint["angle"].get<double>() - joint["angle_input"].get<double>()) > 1e-9;
    ++checked;
  }
  CHECK(checked == 16);
  CHECK(moved > 0);  // the sagging grid's joints turned
  for (const auto& rod : f["rods"])
    CHECK(rod["length"].get<double>() == doctest::Approx(1.0).epsilon(1e-12));
  fs::remove_all(dir);
}

TEST_CASE("fabricate: invalid input exits 2 and an unwritable output 4") {
  const ScratchDirectory scratch("fabricate-bad");
  const fs::path& dir = scratch.path();
  FabricateArguments args;
  args.config = (dir / "missing.json").string();
  CHECK(run_fabricate(args) == kExitInvalidInput);

  write_text(dir / "run.json", sample_config(dir / "out"));
  args.config = (dir / "run.json").string();
  write_text(dir / "other.json", R"({"format": "xshell-state", "version": 1})");
  args.init = (dir / "other.json").string();
  CHECK(run_fabricate(args) == kExitInvalidInput);
  CHECK(!fs::exists(dir / "out"));

  args.init.reset();
  write_text(dir / "a_file", "not a directory");
  args.out = (dir / "a_file" / "out").string();
  CHECK(run_fabricate(args) == kExitOutputFailed);
  fs::remove_all(dir);
}

}  // namespace xshell::test
