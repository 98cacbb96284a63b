// Helpers of the rendering tests: options of a given size, and the pixels of
// a PNG picture, for checks of what a picture shows.
#pragma once

#include <array>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "io/vtk/render_png.hpp"

namespace xshell::test {

// Default options but for the size and the colour array.
RenderOptions sized(int width, int height, const std::string& color);

using Rgb = std::array<int, 3>;

struct Pixels {
  int width = 0, height = 0;
  std::vector<Rgb> rgb;  // row after row, from the bottom row up (VTK's order)

  const Rgb& at(int x, int y) const { return rgb[static_cast<size_t>(y) * width + x]; }
  std::set<unsigned> colours() const;  // packed RGB
  // The share of the pixels of rows [y0, y1) that are not the white background.
  double drawn_fraction(int y0, int y1) const;
  double drawn_fraction() const { return drawn_fraction(0, height); }
  // The share of pixels that differ from `other`'s (of the same size).
  double differing_fraction(const Pixels& other) const;
};

// A colour far from grey: its largest and smallest channels differ by more
// than 60 (of 255).
bool saturated(const Rgb& c);

// Reads `path` (REQUIRE: a PNG of at least 3 channels).
Pixels read_pixels(const std::filesystem::path& path);

}  // namespace xshell::test
