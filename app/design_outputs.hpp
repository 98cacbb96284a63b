// What `xshell design` reports and writes (README, "Design"): design.json,
// the optimized design's deployed and flat states (deployed_state.json,
// flat_state.json, each a state.json), a VTK series of two steps (time 0
// the flat state, time 1 the deployed one, its joints carrying
// `target_distance`), the flat layout as an OBJ line mesh (flat_layout.obj:
// the linkage's vertices where the flat state puts them, its edges) and the
// flat state's fabrication data (fabrication.json, .csv, .svg).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "integrators/design/design_loop.hpp"
#include "integrators/design/design_scales.hpp"
#include "io/config.hpp"

namespace xshell {

struct DesignReport {
  const DesignLoopResult& result;
  DesignScales scales;
  const DesignObjective& objective;  // its deployed equilibrium and targets: the result's
  const LinkageProblem& flat;        // the flat equilibrium of the result
  bool flat_planar = false;          // the flat state was held in its plane
  std::string warning;               // empty: none
  double wall_seconds = 0.0;
};

// One element of design.json's "history": the unit-free terms (as weighted),
// the fit's rms distance (length), IPOPT's optimality measure, evaluations
// and seconds so far.
nlohmann::json history_record(const DesignIteration& it, const DesignScales& scales, int targets);

// design.json's content.
nlohmann::json design_report_json(const DesignReport& report, const Config& config);

// Writes every file above into config.output.directory (which exists), design.json
// last; `design` is design.json's content, the states state.json texts
// (state_text). Throws OutputError naming the file that failed.
void write_design_outputs(const DesignReport& report, const Config& config,
                          const Eigen::Vector3d& origin, const nlohmann::json& design,
                          const std::string& deployed_state, const std::string& flat_state);

}  // namespace xshell
