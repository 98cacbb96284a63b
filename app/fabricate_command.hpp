// `xshell fabricate CONFIG.json [--init STATE.json] [--out DIR]`: writes the
// fabrication files (io/fabrication_file.hpp) of the configuration's linkage,
// as drawn or in a state saved by an earlier run, without solving.
#pragma once

#include <optional>
#include <string>

namespace xshell {

struct FabricateArguments {
  std::string config;               // path of the configuration
  std::optional<std::string> out;   // output directory (relative to the working directory)
  std::optional<std::string> init;  // a state.json to take the current state from
};

// Runs the command; returns the exit status (exit_status.hpp): 0 written,
// 2 invalid input (configuration, linkage or state), 4 an output failed.
int run_fabricate(const FabricateArguments& arguments);

}  // namespace xshell
