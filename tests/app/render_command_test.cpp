// `xshell render` through the real program: bad input (a file that is no
// VTK PolyData, an option out of range, an unknown colour array) is exit
// status 2 with one line "xshell: error: ..."; 4 only when the picture
// cannot be made or written. Input is checked before the display is opened,
// so these hold with or without one; the picture itself needs a display
// (the suite runs under xvfb-run).
#include <doctest/doctest.h>

#include "reliability_support.hpp"
#include "skip.hpp"

namespace xshell::test {

namespace {

// A relaxed grid sample in `dir`/run (its rods_*.vtp and solids_*.vtp).
void relax_sample(const ScratchDirectory& dir) {
  write_text(dir / "run.json", sample_config(dir / "run", R"(, "solver": {"max_iterations": 3})"));
  const CommandResult r = run_xshell("relax run.json", dir.path());
  INFO("stderr: " << r.errors);
  REQUIRE((r.status == 0 || r.status == 3));
}

void check_status(const CommandResult& r, int status, const std::vector<std::string>& words) {
  INFO("stderr: " << r.errors);
  CHECK(r.status == status);
  CHECK(r.errors.rfind("xshell: error: ", 0) == 0);
  CHECK(count_lines(r.errors) == 1);
  for (const auto& w : words) CHECK_MESSAGE(contains(r.errors, w), "missing: " << w);
}

}  // namespace

TEST_CASE("render command: input that is no VTK PolyData is invalid input (status 2)") {
  ScratchDirectory dir("render-input");
  relax_sample(dir);
  const std::string rods = read_text(dir / "run" / "rods_000000.vtp");
  REQUIRE(rods.size() > 1000);
  write_text(dir / "truncated.vtp", rods.substr(0, rods.size() / 2));
  std::string garbage;
  for (int i = 0; i < 4096; ++i) garbage += static_cast<char>((i * 37 + 11) % 256);
  write_text(dir / "garbage.vtp", garbage);
  write_text(dir / "empty.vtp", "");
  fs::create_directory(dir / "no_steps");
  struct Case {
    std::string input, words;
  };
  const std::vector<Case> cases = {
      {"run/summary.json", "'run/summary.json': not a VTK XML PolyData file"},
      {"truncated.vtp", "'truncated.vtp'"},
      {"garbage.vtp", "'garbage.vtp': not a VTK XML PolyData file"},
      {"empty.vtp", "'empty.vtp': the file is empty"},
      {"missing.vtp", "'missing.vtp': no such file"},
      {"no_steps", "no_steps: no rods_*.vtp or solids_*.vtp files"},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.input);
    check_status(run_xshell_limited("render " + c.input + " --out p.png", dir.path(), 60), 2,
                 {c.words});
    CHECK_FALSE(fs::exists(dir / "p.png"));
    ++checked;
  }
  CHECK(checked == 6);
}

TEST_CASE("render command: options out of range are invalid input (status 2)") {
  ScratchDirectory dir("render-options");
  relax_sample(dir);
  struct Case {
    std::string options, words;
  };
  const std::vector<Case> cases = {
      {"--width 0", "--width: must be 1 to 8192 pixels, got 0"},
      {"--width -5", "--width"},
      {"--height 0", "--height: must be 1 to 8192 pixels, got 0"},
      {"--width 100000", "--width: must be 1 to 8192 pixels, got 100000"},
      {"--height 20000", "--height: must be 1 to 8192"},
      {"--width many", "--width"},
      {"--color no_such_array",
       "no drawn input has an array named 'no_such_array' to colour by; the arrays are: "
       "Normals, bending_density, curvature"},
      {"--view diagonal", "--view"},
      {"--scale-deflection -1", "--scale-deflection"},
      {"--scale-deflection nan", "--scale-deflection: must be a finite number"},
      {"--scale-deflection 1e400", "--scale-deflection"},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.options);
    check_status(run_xshell_limited("render run --out p.png " + c.options, dir.path(), 60), 2,
                 {c.words});
    CHECK_FALSE(fs::exists(dir / "p.png"));
    ++checked;
  }
  CHECK(checked == 11);
}

TEST_CASE(
    "render command: a picture that cannot be written is status 4 and a written one 0 (needs a "
    "display)") {
  ScratchDirectory dir("render-output");
  relax_sample(dir);
  // Without a display the picture cannot be made: 4 as well.
  check_status(run_xshell_limited("render run --out no_folder/p.png", dir.path(), 60), 4, {});
  if (!std::getenv("DISPLAY")) XSHELL_SKIP("DISPLAY is not set: no picture is drawn");
  const CommandResult r =
      run_xshell_limited("render run --out p.png --width 64 --height 48", dir.path(), 60);
  CAPTURE(r.errors);
  CHECK(r.status == 0);
  CHECK(fs::file_size(dir / "p.png") > 0);
  CHECK(contains(r.errors, "xshell: wrote p.png"));
}

TEST_CASE(
    "render command: views and an exaggerated deflection and a joints-only file draw and no "
    "reference geometry is status 2 (needs a display)") {
  ScratchDirectory dir("render-views");
  relax_sample(dir);
  fs::create_directory(dir / "alone");
  fs::copy_file(dir / "run" / "joints_000001.vtp", dir / "alone" / "joints_000001.vtp");
  check_status(run_xshell_limited("render alone/joints_000001.vtp --out p.png --scale-deflection 5",
                                  dir.path(), 60),
               2, {"--scale-deflection: no reference geometry for 'alone/joints_000001.vtp'"});
  if (!std::getenv("DISPLAY")) XSHELL_SKIP("DISPLAY is not set: no picture is drawn");
  const std::vector<std::string> commands = {
      "render run --out p.png --view top --width 96 --height 64",
      "render run --out p.png --view front --scale-deflection 20 --width 96 --height 64",
      "render run --out p.png --view side --color curvature --width 96 --height 64",
      "render alone/joints_000001.vtp --out p.png --width 96 --height 64",
      "render run/joints_000001.vtp --out p.png --scale-deflection 0 --color opening_angle"};
  for (const std::string& command : commands) {
    CAPTURE(command);
    fs::remove(dir / "p.png");
    const CommandResult r = run_xshell_limited(command, dir.path(), 60);
    CAPTURE(r.errors);
    CHECK(r.status == 0);
    CHECK(fs::is_regular_file(dir / "p.png"));
  }
}

}  // namespace xshell::test
