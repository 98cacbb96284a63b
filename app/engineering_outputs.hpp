// The engineering results of a converged run: support reactions, rod
// stresses, joint forces, the lowest eigenvalues and the buckling load
// factor (linkage/reactions.hpp, linkage/rod_stresses.hpp,
// linkage/joint_forces.hpp, integrators/stability_analysis.hpp), into
// summary.json (RunSummary::engineering) and the VTK files of
// io/vtk/engineering_files.hpp.
#pragma once

#include <Eigen/Core>
#include <filesystem>

#include "io/config.hpp"
#include "io/summary_file.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

// problem: at its final (converged) state. origin: added to positions.
// Throws OutputError when a file cannot be written.
void write_engineering_results(LinkageProblem& problem, const Config& config,
                               const Eigen::Vector3d& origin,
                               const std::filesystem::path& directory, RunSummary& summary);

}  // namespace xshell
