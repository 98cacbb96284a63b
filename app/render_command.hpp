// `xshell render OUTPUT_DIR|FILE.vtp... --out PICTURE.png`: a headless
// picture of a run's final state. Debian's VTK renders through X: run it
// under `xvfb-run -a` on a machine without a display.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace xshell {

struct RenderArguments {
  std::vector<std::string> inputs;
  std::string png;
  int width = 1024, height = 768;
  std::string color = "bending_density";
  bool color_given = false;  // --color given: an array no input has is an error
  std::string view = "iso";  // iso | top | front | side
  std::optional<double> scale_deflection;
};

int run_render(const RenderArguments& arguments);

}  // namespace xshell
