// `xshell design CONFIG.json [--out DIR] [--init STATE.json] [--quiet]`: the
// inverse design (README, "Design"): the segment rest lengths whose deployed
// shell fits the configuration's "design" target (design_run.hpp).
#pragma once

#include <atomic>
#include <optional>
#include <string>

namespace xshell {

struct DesignArguments {
  std::string config;               // path of the configuration
  std::optional<std::string> out;   // output directory (overrides output.directory)
  std::optional<std::string> init;  // a state.json of the flat linkage to start from
  bool quiet = false;               // no progress lines
};

// Runs the command; returns the exit status (exit_status.hpp): 0 the
// optimizer converged, 2 invalid input, 3 iteration limit or failure (the
// best design found is written), 4 an output failed, 130 interrupted (the
// best design so far is written).
int run_design_command(const DesignArguments& arguments, const std::atomic<bool>& stop);

}  // namespace xshell
