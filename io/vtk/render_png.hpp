// Headless rendering of written .vtp files to a PNG picture, for reports and
// quick looks without ParaView.
//
// Surfaces (the solids file) are drawn when any input has polygons;
// otherwise polylines (the rods file) are drawn as tubes. Vertex-only files
// (frames, joints) are ignored. Surfaces are coloured by a point or cell
// array through a blue-to-red lookup table over the array's range across the
// drawn inputs, on a white background, seen from an isometric-like direction
// (1, -1, 0.8) with z up, zoomed to fit.
//
// Needs an X display, even off screen (see x_display.hpp): run the command
// under `xvfb-run -a` on a machine without one.
#pragma once

#include <string>
#include <vector>

namespace xshell {

// Largest width or height of a picture, in pixels (beyond, X servers and
// OpenGL drivers refuse the window, some with an error that ends the
// process).
constexpr int kMaxPictureSide = 8192;

struct RenderOptions {
  int width = 1024;  // pixels, 1 to kMaxPictureSide
  int height = 768;  // pixels, 1 to kMaxPictureSide
  // Point or cell array to colour by; empty: one colour for everything.
  std::string color_array = "bending_density";
  // Tube radius for polylines (length unit); 0: 0.4% of the bounding-box
  // diagonal of the inputs.
  double tube_radius = 0.0;
};

// vtp_files: .vtp files (rods_*.vtp, solids_*.vtp, ...); png_path: the picture
// to write (replaced atomically). Throws InputError for bad input (a size out
// of range, a file that is missing, empty, not VTK PolyData, truncated or
// malformed, no input with polygons or polylines, no drawn input carrying
// `color_array`); RenderError when the picture cannot be made (no X display,
// no renderer); OutputError naming png_path when it cannot be written.
void render_png(const std::vector<std::string>& vtp_files, const std::string& png_path,
                const RenderOptions& options = {});

}  // namespace xshell
