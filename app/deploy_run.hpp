// `xshell relax` on a configuration with a "deployment": the continuation of
// integrators/deployment.hpp and its outputs, besides the run's usual ones:
//   - one VTK snapshot per accepted step (time = step index: 0 is the start
//     in equilibrium at its own angle), through the run's series;
//   - deployment.csv, one row per accepted step, header
//       step,average_angle,energy_total,energy_stretching,energy_bending,
//       energy_twisting,torque,iterations,stable
//     (radians; energies in the configuration's units; torque dE/dA in
//     energy per radian; stable true/false), rewritten atomically after
//     every step, so an interrupted run keeps the steps it finished;
//   - deployment.png, energy and torque against the angle (deployment_plot.hpp);
//   - the summary's "deployment" object and run fields: status "converged"
//     when every step converged, iterations over all steps, history with
//     every solver iteration (time = the step being solved).
// A restart (--init STATE.json) continues from the saved state's angle: to a
// larger target it opens further, to a smaller one it closes.
#pragma once

#include <filesystem>
#include <optional>

#include "io/config.hpp"
#include "io/summary_file.hpp"
#include "linkage/statics_problem.hpp"
#include "solver_runs.hpp"

namespace xshell {

// Readies `problem` (built from `statics`) for config.deployment, if any:
// with "joint_angles" it is rebuilt on the same linkage state with an
// "opening_angle" support at every listed vertex, whose angles are then
// driven rather than solved for (a default pin is kept as an explicit
// support); with "average_opening_angle" at least one opening angle must be
// free. Throws InputError naming the key for a free rod end or an average
// that nothing can move.
void prepare_deployment(const Config& config, std::optional<LinkageProblem>& problem,
                        StaticsSetup statics);

// Runs config.deployment on `problem` (readied by prepare_deployment),
// writing deployment.csv and deployment.png into `dir` (none when `dir` is
// empty: a run that writes no files) and a VTK step per
// accepted step through hooks.snapshot. The result's status is the summary's
// ("converged" when every step converged), its reason "deployment
// <completed|step failed|interrupted>: ..."; the run's deployment object is
// the summary's "deployment".
SolverRun run_deployment(const Config& config, LinkageProblem& problem,
                         const std::filesystem::path& dir, const RunHooks& hooks);

}  // namespace xshell
