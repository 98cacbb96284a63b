#include "render_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "exit_status.hpp"
#include "io/vtk/render_png.hpp"

namespace xshell {

namespace {
namespace fs = std::filesystem;

// The last step's solids file of an output directory, else its rods file.
std::string final_step_file(const fs::path& dir) {
  std::vector<std::string> solids, rods;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".vtp") continue;
    if (name.rfind("solids_", 0) == 0) solids.push_back(entry.path().string());
    if (name.rfind("rods_", 0) == 0) rods.push_back(entry.path().string());
  }
  auto& files = solids.empty() ? rods : solids;
  if (files.empty()) return {};
  return *std::max_element(files.begin(), files.end());
}
}  // namespace

int run_render(const RenderArguments& args) {
  std::vector<std::string> files;
  for (const std::string& input : args.inputs) {
    if (fs::is_directory(input)) {
      const std::string f = final_step_file(input);
      if (f.empty()) {
        std::cerr << "xshell: error: " << input << ": no rods_*.vtp or solids_*.vtp files\n";
        return kExitInvalidInput;
      }
      files.push_back(f);
    } else {
      files.push_back(input);
    }
  }
  RenderOptions options;
  options.width = args.width;
  options.height = args.height;
  options.color_array = args.color;
  try {
    render_png(files, args.png, options);
  } catch (const std::exception& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitOutputFailed;
  }
  std::cerr << "xshell: wrote " << args.png << "\n";
  return kExitConverged;
}

}  // namespace xshell
