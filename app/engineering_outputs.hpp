// The engineering results of a converged run: support reactions, rod
// stresses, joint forces, the lowest eigenvalues and the buckling load
// factor (linkage/reactions.hpp, linkage/rod_stresses.hpp,
// linkage/joint_forces.hpp, integrators/stability_analysis.hpp), into
// summary.json (RunSummary::engineering) and the VTK files of
// io/vtk/engineering_files.hpp.
#pragma once

#include <Eigen/Core>
#include <filesystem>

#include "integrators/stability/stability_analysis.hpp"
#include "io/config.hpp"
#include "io/summary_file.hpp"
#include "io/vtk/engineering_snapshot.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

// Computes them into summary.engineering, writing no file; returns what the
// VTK files of write_engineering_results show. problem: at its final
// (converged) state. origin: added to positions.
// The stability analysis runs with config.analysis (its budget from now)
// and reports to `on_progress` (may be empty); a budget that ran out is
// said in the summary's warnings. factorized: the solve's CHOLMOD solver
// (StabilityOptions::factorized), or nullptr.
EngineeringSnapshot engineering_results(
    LinkageProblem& problem, const Config& config, const Eigen::Vector3d& origin,
    RunSummary& summary, const std::function<void(const StabilityProgress&)>& on_progress = {},
    CholeskySolver* factorized = nullptr);

// The VTK files of `snapshot` into `directory`. Throws OutputError when a
// file cannot be written.
void write_engineering_files(const EngineeringSnapshot& snapshot, const Config& config,
                             const std::filesystem::path& directory);

// Both.
void write_engineering_results(LinkageProblem& problem, const Config& config,
                               const Eigen::Vector3d& origin,
                               const std::filesystem::path& directory, RunSummary& summary);

}  // namespace xshell
