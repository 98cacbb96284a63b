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

// The last step's solids file of an output directory, else its rods file.
std::string final_step_file(const fs::path& dir) {
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
  return *std::max_element(files.begin(), files.end());
}

void check_side(const char* option, int pixels) {
  if (pixels < 1 || pixels > kMaxPictureSide)
    throw InputError(std::string(option) + ": must be 1 to " + std::to_string(kMaxPictureSide) +
                     " pixels, got " + std::to_string(pixels));
}
}  // namespace

// Exit statuses: 2 for invalid input (an option, a file that is missing or
// not VTK PolyData, nothing to draw, an unknown colour array), 4 when the
// picture cannot be made or written (no X display, the PNG file).
int run_render(const RenderArguments& args) {
  RenderOptions options;
  options.width = args.width;
  options.height = args.height;
  options.color_array = args.color;
  try {
    check_side("--width", args.width);
    check_side("--height", args.height);
    std::vector<std::string> files;
    for (const std::string& input : args.inputs) {
      std::error_code ignored;
      files.push_back(fs::is_directory(input, ignored) ? final_step_file(input) : input);
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
