#include "render_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "exit_status.hpp"
#include "io/input_error.hpp"
#include "io/output_error.hpp"
#include "io/vtk/render_error.hpp"
#include "io/vtk/render_png.hpp"

namespace xshell {

namespace {
namespace fs = std::filesystem;

// The last step's solids file of an output directory, else its rods file;
// and its reactions.vtp when there is one.
std::vector<std::string> final_step_files(const fs::path& dir) {
  std::vector<std::string> solids, rods;
  std::error_code error;
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
    const fs::path& path = it->path();
    const std::string name = path.filename().string();
    if (path.extension() != ".vtp") continue;
    if (name.rfind("solids_", 0) == 0) solids.push_back(path.string());
    if (name.rfind("rods_", 0) == 0) rods.push_back(path.string());
  }
  if (error)
    throw InputError("render: cannot read the folder '" + printable(dir.string()) +
                     "': " + error.message());
  auto& files = solids.empty() ? rods : solids;
  if (files.empty())
    throw InputError(printable(dir.string()) + ": no rods_*.vtp or solids_*.vtp files");
  std::vector<std::string> chosen = {*std::max_element(files.begin(), files.end())};
  if (fs::is_regular_file(dir / "reactions.vtp", error)) chosen.push_back(dir / "reactions.vtp");
  return chosen;
}

RenderView view_named(const std::string& name) {
  if (name == "top") return RenderView::Top;
  if (name == "front") return RenderView::Front;
  if (name == "side") return RenderView::Side;
  if (name == "iso") return RenderView::Iso;
  throw InputError("--view: must be iso, top, front or side, got '" + printable(name) + "'");
}

void check_side(const char* option, int pixels) {
  if (pixels < 1 || pixels > kMaxPictureSide)
    throw InputError(std::string(option) + ": must be 1 to " + std::to_string(kMaxPictureSide) +
                     " pixels, got " + std::to_string(pixels));
}
}  // namespace

// Exit statuses: 2 for invalid input (an option, a file that is missing or
// not VTK PolyData, nothing to draw, an unknown colour array, no reference
// geometry for --scale-deflection), 4 when the picture cannot be made or
// written (no X display, the PNG file).
int run_render(const RenderArguments& args) {
  RenderOptions options;
  options.width = args.width;
  options.height = args.height;
  options.color_array = args.color;
  options.color_optional = !args.color_given;
  options.scale_deflection = args.scale_deflection;
  try {
    options.view = view_named(args.view);
    check_side("--width", args.width);
    check_side("--height", args.height);
    std::vector<std::string> files;
    for (const std::string& input : args.inputs) {
      std::error_code ignored;
      if (!fs::is_directory(input, ignored)) {
        files.push_back(input);
        continue;
      }
      for (std::string& file : final_step_files(input)) files.push_back(std::move(file));
    }
    render_png(files, args.png, options);
  } catch (const InputError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitInvalidInput;
  } catch (const OutputError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitOutputFailed;
  } catch (const RenderError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitOutputFailed;
  }
  std::cerr << "xshell: wrote " << args.png << "\n";
  return kExitConverged;
}

}  // namespace xshell
