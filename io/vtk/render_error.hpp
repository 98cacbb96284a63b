// The exception of headless rendering (render_png.hpp): no X display to
// render through, an input file that cannot be read, nothing to draw, or a
// colour array that no input carries. Failing to write the picture itself is
// an OutputError.
#pragma once

#include <stdexcept>
#include <string>

namespace xshell {

class RenderError : public std::runtime_error {
 public:
  explicit RenderError(const std::string& message);
};

}  // namespace xshell
