#include "fabricate_command.hpp"

#include <filesystem>
#include <iostream>
#include <system_error>

#include "exit_status.hpp"
#include "io/config.hpp"
#include "io/fabrication_file.hpp"
#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/output_error.hpp"
#include "io/problem_setup.hpp"
#include "io/state_file.hpp"
#include "linkage/model_error.hpp"
#include "output_folder.hpp"

namespace xshell {

namespace fs = std::filesystem;

int run_fabricate(const FabricateArguments& args) {
  // The linkage as `relax` builds it (the same readers and setup), so that
  // rods and joints are numbered alike and a state of a run restores.
  Config config;
  std::optional<RodLinkage> linkage;
  try {
    config = read_config(args.config);
    if (args.out) config.output.directory = fs::absolute(*args.out).string();
    const LineGraph graph = read_obj(config.linkage);
    const ProblemSetup setup = make_problem_setup(config, graph);
    linkage.emplace(setup.graph, setup.options);
    if (args.init) read_state(*args.init, *linkage, setup.origin);
  } catch (const InputError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitInvalidInput;
  } catch (const ModelError& e) {
    std::cerr << "xshell: error: " << (config.linkage.empty() ? args.config : config.linkage)
              << ": " << e.what() << "\n";
    return kExitInvalidInput;
  }

  const fs::path dir = config.output.directory;
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) {
    std::cerr << "xshell: error: cannot write the output directory: cannot create '" << dir.string()
              << "': " << error.message() << "\n";
    return kExitOutputFailed;
  }
  try {
    const OutputFolderLock lock(dir);  // not while a run writes there
    write_fabrication(*linkage, fabrication_units(config), dir);
  } catch (const OutputError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitOutputFailed;
  }
  std::cerr << "xshell: fabrication data of " << linkage->topology().rods.size() << " rods and "
            << linkage->num_joints() << " joints ("
            << (args.init ? "state " + *args.init : std::string("as drawn"))
            << "): fabrication.json, fabrication.csv, fabrication.svg in " << dir.string() << "\n";
  return kExitConverged;  // 0: written
}

}  // namespace xshell
