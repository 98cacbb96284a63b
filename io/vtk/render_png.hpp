// Headless rendering of written .vtp files to a PNG picture, for reports and
// quick looks without ParaView.
//
// Surfaces (the solids file) are drawn when any input has polygons;
// otherwise polylines (the rods file, stresses.vtp) are drawn as tubes.
// Point files are drawn as glyphs: spheres at joints (joints_*.vtp,
// joint_forces.vtp), arrows along the reaction forces (reactions.vtp).
// Everything is coloured by a point or cell array through a blue-to-red
// lookup table over the array's range across the drawn inputs, with a colour
// bar titled with the array's name and unit, on a white background, seen
// from a preset direction, zoomed to fit.
//
// Needs an X display, even off screen (see x_display.hpp): run the command
// under `xvfb-run -a` on a machine without one.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace xshell {

// Largest width or height of a picture, in pixels (beyond, X servers and
// OpenGL drivers refuse the window, some with an error that ends the
// process).
constexpr int kMaxPictureSide = 8192;

// Where the camera looks from (z up unless said otherwise):
enum class RenderView {
  Iso,    // from (1, -1, 0.8): the x axis to the right and front, y away
  Top,    // down -z, y up in the picture
  Front,  // along +y (the eye at -y)
  Side,   // along -x (the eye at +x), y to the right
};

struct RenderOptions {
  int width = 1024;  // pixels, 1 to kMaxPictureSide
  int height = 768;  // pixels, 1 to kMaxPictureSide
  // Point or cell array to colour by; empty: one colour for everything.
  std::string color_array = "bending_density";
  // Tube radius for polylines (length unit); 0: 0.4% of the bounding-box
  // diagonal of the inputs.
  double tube_radius = 0.0;
  // When no drawn input has color_array: one colour (true) or an InputError.
  bool color_optional = false;
  RenderView view = RenderView::Iso;
  // Draw reference + k (position - reference), the reference being the
  // run's first written step (render_inputs.hpp); none: as written.
  std::optional<double> scale_deflection;
};

// vtp_files: .vtp files (rods_*.vtp, solids_*.vtp, joints_*.vtp,
// reactions.vtp, stresses.vtp, ...); png_path: the picture to write
// (replaced atomically). Throws InputError for bad input (a size out of
// range, a file that is missing, empty, not VTK PolyData, truncated or
// malformed, nothing to draw, no drawn input carrying `color_array` (the
// message lists the arrays there are), a negative or non-finite
// scale_deflection or no reference geometry for it); RenderError when the
// picture cannot be made (no X display, no renderer); OutputError naming
// png_path when it cannot be written.
void render_png(const std::vector<std::string>& vtp_files, const std::string& png_path,
                const RenderOptions& options = {});

}  // namespace xshell
