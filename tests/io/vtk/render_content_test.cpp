// What a rendered picture shows, read from its pixels: the colour bar, the
// linkage's share of the picture from every view, the exaggerated
// deflection, joints and reactions as glyphs; and the colour bar's title
// with its unit. The pictures need an X display (CI runs the suite under
// `xvfb-run -a`); the rest is checked everywhere.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>

#include "demo_snapshot.hpp"
#include "io/input_error.hpp"
#include "io/vtk/engineering_files.hpp"
#include "io/vtk/joints_file.hpp"
#include "io/vtk/render_scene.hpp"
#include "io/vtk/rods_file.hpp"
#include "io/vtk/x_display.hpp"
#include "render_test_support.hpp"
#include "skip.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {
namespace {

namespace fs = std::filesystem;

void require_display() {
  if (!display_variable_set())
    XSHELL_SKIP("DISPLAY is not set: no picture (run under `xvfb-run -a` to check it)");
}

Pixels render(const std::vector<fs::path>& files, const fs::path& png,
              const RenderOptions& options) {
  std::vector<std::string> names;
  for (const fs::path& f : files) names.push_back(f.string());
  render_png(names, png.string(), options);
  return read_pixels(png);
}

// Four supports at the grid's corners, each taking a quarter of a unit load.
EngineeringSnapshot corner_reactions(const Snapshot& grid, int n) {
  EngineeringSnapshot e;
  for (int vertex : {0, n - 1, n * (n - 1), n * n - 1}) {
    ReactionGlyph r;
    r.vertex = vertex;
    r.position = grid.joints[vertex].position;
    r.force = Eigen::Vector3d(0.0, 0.0, 0.25);
    e.reactions.push_back(r);
  }
  return e;
}

// A reddish pixel: the reaction arrows' colour, no other on a colourless
// picture.
long red_pixels(const Pixels& p) {
  return std::count_if(p.rgb.begin(), p.rgb.end(),
                       [](const Rgb& c) { return c[0] > 150 && c[1] < 90 && c[2] < 90; });
}

}  // namespace

TEST_CASE("render: the colour bar spans blue to red under the drawing (needs a display)") {
  require_display();
  ScratchDirectory dir("render_bar");
  const fs::path rods = dir.path() / "rods_000000.vtp";
  write_rods_file(grid_snapshot(5, 0.2), rods);
  const Pixels colored = render({rods}, dir.path() / "bar.png", sized(400, 300, "bending_density"));
  // The bar's row: the most saturated one of the bottom 16%.
  int best_row = -1, best_count = 0;
  for (int y = 0; y < 48; ++y) {
    int count = 0;
    for (int x = 0; x < colored.width; ++x) count += saturated(colored.at(x, y));
    if (count > best_count) best_row = y, best_count = count;
  }
  REQUIRE(best_row >= 0);
  std::vector<Rgb> row;
  std::set<unsigned> distinct;
  for (int x = 0; x < colored.width; ++x)
    if (saturated(colored.at(x, best_row))) {
      const Rgb& c = colored.at(x, best_row);
      row.push_back(c);
      distinct.insert(static_cast<unsigned>(c[0] << 16 | c[1] << 8 | c[2]));
    }
  MESSAGE("colour bar row " << best_row << ": " << best_count << " coloured pixels, "
                            << distinct.size() << " colours");
  CHECK(best_count > 0.6 * 0.8 * colored.width);  // the bar is 80% of the width
  CHECK(distinct.size() > 30);
  CHECK(row.front()[2] > row.front()[0] + 60);  // blue at the left end (low)
  CHECK(row.back()[0] > row.back()[2] + 60);    // red at the right end (high)

  // No colour array: no bar, and nothing saturated anywhere.
  const Pixels plain = render({rods}, dir.path() / "plain.png", sized(400, 300, ""));
  CHECK(std::none_of(plain.rgb.begin(), plain.rgb.end(), saturated));
}

TEST_CASE(
    "render: a flat and a deployed linkage fill the picture from every view (needs a display)") {
  require_display();
  ScratchDirectory dir("render_views");
  int checked = 0;
  for (double height : {0.0, 0.25}) {
    const fs::path rods = dir.path() / "rods_000000.vtp";
    write_rods_file(grid_snapshot(6, height), rods);
    for (RenderView view :
         {RenderView::Iso, RenderView::Top, RenderView::Front, RenderView::Side}) {
      RenderOptions options = sized(320, 240, "");
      options.view = view;
      const double drawn = render({rods}, dir.path() / "view.png", options).drawn_fraction();
      CAPTURE(height);
      CAPTURE(static_cast<int>(view));
      MESSAGE("height " << height << ", view " << static_cast<int>(view) << ": " << drawn
                        << " of the pixels drawn");
      CHECK(drawn > 0.02);
      ++checked;
    }
  }
  CHECK(checked == 8);
}

TEST_CASE(
    "render: --scale-deflection draws the displacement from the first step K times (needs a "
    "display)") {
  require_display();
  ScratchDirectory dir("render_deflection");
  const fs::path start = dir.path() / "rods_000000.vtp", last = dir.path() / "rods_000004.vtp";
  write_rods_file(grid_snapshot(5, 0.0), start);
  write_rods_file(grid_snapshot(5, -0.004), last);  // a 4 mm sag of a 1 m grid
  RenderOptions options = sized(320, 240, "");
  options.view = RenderView::Front;
  const Pixels plain = render({last}, dir.path() / "plain.png", options);
  const Pixels flat = render({start}, dir.path() / "flat.png", options);
  options.scale_deflection = 1.0;
  const Pixels once = render({last}, dir.path() / "once.png", options);
  options.scale_deflection = 0.0;
  const Pixels none = render({last}, dir.path() / "none.png", options);
  options.scale_deflection = 100.0;
  const Pixels hundred = render({last}, dir.path() / "hundred.png", options);
  CHECK(once.differing_fraction(plain) == 0.0);  // K = 1: as written
  CHECK(none.differing_fraction(flat) == 0.0);   // K = 0: the first step
  MESSAGE("K = 100 changes " << hundred.differing_fraction(plain) << " of the pixels");
  CHECK(hundred.differing_fraction(plain) > 0.05);
}

TEST_CASE("render: --scale-deflection without reference geometry is an InputError") {
  ScratchDirectory dir("render_no_reference");
  fs::create_directory(dir.path() / "lone");
  const fs::path lone = dir.path() / "lone" / "rods_000004.vtp";
  const fs::path other = dir.path() / "other.vtp";
  write_rods_file(grid_snapshot(3, 0.0), lone);
  write_rods_file(grid_snapshot(3, 0.0), other);
  write_rods_file(grid_snapshot(4, 0.0), dir.path() / "rods_000000.vtp");
  write_rods_file(grid_snapshot(3, 0.1), dir.path() / "rods_000002.vtp");
  RenderOptions options = sized(64, 48, "");
  options.scale_deflection = 10.0;
  const std::string png = (dir.path() / "p.png").string();
  CHECK_THROWS_WITH_AS(render_png({lone.string()}, png, options),
                       doctest::Contains("rods_000000.vtp' is missing"), InputError);
  CHECK_THROWS_WITH_AS(render_png({other.string()}, png, options),
                       doctest::Contains("no reference geometry for"), InputError);
  CHECK_THROWS_WITH_AS(render_png({(dir.path() / "rods_000002.vtp").string()}, png, options),
                       doctest::Contains("has 104 points, it has 54"), InputError);
  options.scale_deflection = -1.0;
  CHECK_THROWS_WITH_AS(render_png({other.string()}, png, options),
                       doctest::Contains("must be a finite number >= 0"), InputError);
  CHECK_FALSE(fs::exists(png));
}

TEST_CASE("render: joints alone as spheres and reactions as arrows (needs a display)") {
  require_display();
  ScratchDirectory dir("render_glyphs");
  const Snapshot grid = grid_snapshot(5, 0.2);
  const fs::path joints = dir.path() / "joints_000003.vtp", rods = dir.path() / "rods_000003.vtp";
  const fs::path reactions = dir.path() / "reactions.vtp";
  write_joints_file(grid, joints);
  write_rods_file(grid, rods);
  write_reactions_file(corner_reactions(grid, 5), reactions);

  const Pixels alone = render({joints}, dir.path() / "joints.png", sized(320, 240, ""));
  MESSAGE("joints alone: " << alone.drawn_fraction() << " of the pixels drawn");
  CHECK(alone.drawn_fraction() > 0.01);
  const Pixels colored =
      render({joints}, dir.path() / "angles.png", sized(320, 240, "opening_angle"));
  CHECK(colored.drawn_fraction(48, 240) > 0.01);

  const Pixels without = render({rods}, dir.path() / "rods.png", sized(320, 240, ""));
  const Pixels with = render({rods, reactions}, dir.path() / "reactions.png", sized(320, 240, ""));
  MESSAGE("reaction arrows: " << red_pixels(with) << " red pixels");
  CHECK(red_pixels(without) == 0);
  CHECK(red_pixels(with) > 0.002 * with.width * with.height);
}

TEST_CASE("render: the colour bar's title names the array's unit from the run's units") {
  ScratchDirectory dir("render_units");
  write_rods_file(grid_snapshot(3, 0.1), dir.path() / "rods_000001.vtp");
  EngineeringSnapshot stresses;
  EdgeResult edge;
  edge.b = Eigen::Vector3d(1.0, 0.0, 0.0);
  edge.equivalent_stress = 12.0;
  stresses.edges = {edge};
  write_stresses_file(stresses, dir.path() / "stresses.vtp");
  auto title = [&](const std::string& file, const std::string& array) {
    const std::vector<RenderInput> inputs = {read_render_input((dir.path() / file).string())};
    RenderOptions options;
    options.color_array = array;
    return choose_coloring(inputs, options).title;
  };
  CHECK(title("rods_000001.vtp", "curvature") == "curvature [1/length]");
  CHECK(title("rods_000001.vtp", "segment_id") == "segment_id");
  CHECK(title("stresses.vtp", "equivalent_stress") == "equivalent_stress [force/length^2]");
  std::ofstream(dir.path() / "summary.json")
      << R"({"configuration": {"units": {"length": "mm", "force": "N"}}})";
  CHECK(title("rods_000001.vtp", "curvature") == "curvature [1/mm]");
  CHECK(title("rods_000001.vtp", "bending_density") == "bending_density [N]");
  CHECK(title("stresses.vtp", "equivalent_stress") == "equivalent_stress [MPa]");
  CHECK(title("stresses.vtp", "bending_moment1") == "bending_moment1 [N mm]");
}

}  // namespace xshell::test
