// Headless PNG rendering. The picture itself needs an X display: CI runs the
// suite under `xvfb-run -a`; without a display that case only prints a
// MESSAGE. The error paths (no display, unreachable display, bad input) are
// checked everywhere: bad input is found before the display is opened.
#include "io/vtk/render_png.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>

#include "demo_snapshot.hpp"
#include "io/input_error.hpp"
#include "io/vtk/render_error.hpp"
#include "io/vtk/rods_file.hpp"
#include "io/vtk/solids_file.hpp"
#include "io/vtk/x_display.hpp"
#include "render_test_support.hpp"
#include "skip.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {
namespace {

// Sets (or, with nullopt, unsets) DISPLAY for its lifetime.
class DisplayVariable {
 public:
  explicit DisplayVariable(const std::optional<std::string>& value) {
    if (const char* old = std::getenv("DISPLAY")) saved_ = old;
    if (value)
      ::setenv("DISPLAY", value->c_str(), 1);
    else
      ::unsetenv("DISPLAY");
  }
  DisplayVariable(const DisplayVariable&) = delete;
  DisplayVariable& operator=(const DisplayVariable&) = delete;
  ~DisplayVariable() {
    if (saved_)
      ::setenv("DISPLAY", saved_->c_str(), 1);
    else
      ::unsetenv("DISPLAY");
  }

 private:
  std::optional<std::string> saved_;
};

struct Picture {
  int width = 0, height = 0;
  std::set<unsigned> colours;  // packed RGB
  bool white_corner = false;
};

Picture read_png(const std::filesystem::path& path) {
  const Pixels pixels = read_pixels(path);
  return {pixels.width, pixels.height, pixels.colours(), pixels.at(0, 0) == Rgb{255, 255, 255}};
}

// The demo snapshot's rods and solids files in `dir`.
std::pair<std::string, std::string> demo_files(const ScratchDirectory& dir) {
  const Snapshot snapshot = demo_snapshot(0.0, 0.4);
  const auto rods = dir.path() / "rods.vtp", solids = dir.path() / "solids.vtp";
  write_rods_file(snapshot, rods);
  write_solids_file(snapshot, solids);
  return {rods.string(), solids.string()};
}

}  // namespace

TEST_CASE("render: no display, or an unreachable one, is a RenderError, not a crash") {
  ScratchDirectory dir("render_nodisplay");
  const auto [rods, solids] = demo_files(dir);
  const auto png = dir.path() / "picture.png";
  int checks = 0;
  for (const std::optional<std::string>& value :
       {std::optional<std::string>{}, std::optional<std::string>{""},
        std::optional<std::string>{":31999"}}) {
    CAPTURE(value.value_or("(unset)"));
    DisplayVariable display(value);
    bool thrown = false;
    try {
      render_png({rods}, png.string());
    } catch (const RenderError& e) {
      thrown = true;
      XSHELL_COUNTED_CHECK(checks, std::string(e.what()).find("xvfb-run") != std::string::npos);
    }
    XSHELL_COUNTED_CHECK(checks, thrown);
    XSHELL_COUNTED_CHECK(checks, !std::filesystem::exists(png));
  }
  CHECK(checks == 3 * 3);
}

TEST_CASE("render: solids and tubes to a non-trivial PNG (needs a display)") {
  if (!display_variable_set())
    XSHELL_SKIP("DISPLAY is not set: no picture (run under `xvfb-run -a` to check it)");
  ScratchDirectory dir("render");
  const auto [rods, solids] = demo_files(dir);
  int checks = 0;

  // Solids present: they are drawn, coloured by bending density.
  const auto solid_png = dir.path() / "solids.png";
  render_png({rods, solids}, solid_png.string(), sized(320, 240, "bending_density"));
  const Picture solid = read_png(solid_png);
  XSHELL_COUNTED_CHECK(checks, solid.width == 320);
  XSHELL_COUNTED_CHECK(checks, solid.height == 240);
  XSHELL_COUNTED_CHECK(checks, solid.white_corner);         // white background
  XSHELL_COUNTED_CHECK(checks, solid.colours.size() > 10);  // shaded, coloured geometry

  // Rods only: drawn as tubes, coloured by a cell array, other size.
  const auto tube_png = dir.path() / "tubes.png";
  render_png({rods}, tube_png.string(), sized(200, 150, "rod_id"));
  const Picture tube = read_png(tube_png);
  XSHELL_COUNTED_CHECK(checks, tube.width == 200);
  XSHELL_COUNTED_CHECK(checks, tube.height == 150);
  XSHELL_COUNTED_CHECK(checks, tube.white_corner);
  XSHELL_COUNTED_CHECK(checks, tube.colours.size() > 1);

  // One colour for everything when no array is asked for.
  const auto plain_png = dir.path() / "plain.png";
  render_png({solids}, plain_png.string(), sized(64, 48, ""));
  XSHELL_COUNTED_CHECK(checks, read_png(plain_png).colours.size() > 1);
  CHECK(checks == 9);
}

TEST_CASE("render: bad input is an InputError with or without a display and draws nothing") {
  ScratchDirectory dir("render_bad");
  const auto [rods, solids] = demo_files(dir);
  const std::string png = (dir.path() / "p.png").string();
  const std::string text = [&] {
    std::ifstream in(rods, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  REQUIRE(text.size() > 100);
  const auto truncated = dir.path() / "truncated.vtp";
  std::ofstream(truncated, std::ios::binary) << text.substr(0, text.size() / 2);
  const auto garbage = dir.path() / "garbage.vtp";
  {
    std::ofstream out(garbage, std::ios::binary);
    for (int i = 0; i < 4096; ++i) out << static_cast<char>((i * 37 + 11) % 256);
  }
  const auto empty = dir.path() / "empty.vtp";
  std::ofstream(empty) << "";
  const auto json = dir.path() / "summary.vtp";
  std::ofstream(json) << "{\"status\": \"converged\"}";
  struct Case {
    std::vector<std::string> files;
    RenderOptions options;
    std::string words;
  };
  const std::vector<Case> cases = {
      {{(dir.path() / "missing.vtp").string()}, {}, "no such file"},
      {{dir.path().string()}, {}, "not a regular file"},
      {{empty.string()}, {}, "the file is empty"},
      {{garbage.string()}, {}, "not a VTK XML PolyData file"},
      {{json.string()}, {}, "not a VTK XML PolyData file"},
      {{truncated.string()}, {}, "truncated.vtp"},
      {{rods},
       sized(64, 48, "no_such_array"),
       "no drawn input has an array named 'no_such_array' to colour by; the arrays are: "
       "bending_density, curvature, rod_id, segment_id, twist, twisting_density"},
      {{rods}, sized(0, 48, ""), "must be 1 to 8192 pixels, got 0 x 48"},
      {{rods}, sized(64, -1, ""), "got 64 x -1"},
      {{rods}, sized(100000, 48, ""), "got 100000 x 48"},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.words);
    CHECK_THROWS_WITH_AS(render_png(c.files, png, c.options), doctest::Contains(c.words.c_str()),
                         InputError);
    ++checked;
  }
  CHECK(checked == 10);
  CHECK_FALSE(std::filesystem::exists(png));
}

TEST_CASE("render: the largest picture side is drawn (needs a display)") {
  if (!display_variable_set()) XSHELL_SKIP("DISPLAY is not set: no picture");
  ScratchDirectory dir("render_large");
  const auto [rods, solids] = demo_files(dir);
  const auto png = dir.path() / "wide.png";
  render_png({solids}, png.string(), sized(kMaxPictureSide, 16, ""));
  CHECK(read_png(png).width == kMaxPictureSide);
}

}  // namespace xshell::test
