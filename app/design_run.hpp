// One run of `xshell design` (README, "Design"), as the command line
// (design_command.hpp) and the Python module both run it: read the
// configuration and its "design" section, the linkage, a state to start
// from and the target; deploy the linkage to the design's angle; find the
// segment rest lengths that minimize the design objective
// (integrators/design/design_loop.hpp) with one progress line per design
// iteration; then write design.json and the optimized design's states, VTK
// series, flat layout and fabrication data (design_outputs.hpp).
#pragma once

#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>

#include "integrators/design/design_loop.hpp"

namespace xshell {

struct DesignRequest {
  // As RelaxRequest (relax_run.hpp): the configuration's file, or its text
  // named `config` with relative paths against `base_dir`.
  std::string config;
  std::optional<std::string> config_text;
  std::string base_dir;
  std::optional<std::string> out;   // output folder (relative to the working directory)
  bool write_files = true;          // false: design.json's content is returned, no file written
  std::optional<std::string> init;  // a state.json of the flat linkage to start from
  std::optional<std::string> init_text;
};

struct DesignHooks {
  const std::atomic<bool>* stop = nullptr;  // raised: the optimization stops at its next iteration
  // After every design iteration (and for the start, iteration 0).
  std::function<void(const DesignIteration&, const nlohmann::json& record)> on_iteration;
  std::ostream* log = nullptr;  // "xshell: design: ..." lines (one per iteration), or none
};

struct DesignOutcome {
  int exit_status = 0;  // exit_status.hpp: 0 converged, 2 input, 3 not converged, 4 output, 130
  std::string error;    // for 2 and 4 (and 3 when the start could not be deployed)
  std::optional<nlohmann::json> report;    // design.json's content (a run that optimized)
  std::string deployed_state, flat_state;  // state.json texts of the optimized design
  std::string directory;                   // the output folder (empty: none)
};

DesignOutcome run_design(const DesignRequest& request, const DesignHooks& hooks);

}  // namespace xshell
