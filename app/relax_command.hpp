// `xshell relax CONFIG.json [--solver newton|dynamics] [--out DIR] [--init STATE.json]`
#pragma once

#include <atomic>
#include <optional>
#include <string>

namespace xshell {

struct RelaxArguments {
  std::string config;                 // path of the configuration
  std::optional<std::string> solver;  // "newton" | "dynamics" | "kinetic-damping"
  std::optional<std::string> out;     // output directory (relative to the working directory)
  std::optional<std::string> init;    // a state.json to start from
  bool quiet = false;                 // no progress lines
  bool verbose = false;               // progress lines even when stderr is not a terminal
  std::string progress = "auto";      // --progress: auto | text | plain | json | off
  double grace = 10.0;  // seconds an iteration may go on after SIGINT/SIGTERM (then the last
                        // written step's state is saved and the run ends)
};

// Runs the command; returns the exit status (exit_status.hpp). `stop` is
// raised by SIGINT/SIGTERM.
int run_relax(const RelaxArguments& arguments, const std::atomic<bool>& stop);

}  // namespace xshell
