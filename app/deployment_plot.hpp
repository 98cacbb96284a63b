// deployment.png: energy and torque of a deployment against the average
// opening angle, drawn from deployment.csv by the matplotlib script
// plot_deployment.py, run as a child process with an argument vector (no
// shell). The build copies the script beside the xshell program (and beside
// the Python module's shared object); an installed program finds it in
// ../share/xshell. Optional: when no python3
// with matplotlib is found (Debian: python3-matplotlib), or the script is
// missing, the plot is skipped with a message.
#pragma once

#include <filesystem>
#include <string>

#include "io/unit_names.hpp"

namespace xshell {

struct PlotOutcome {
  bool written = false;
  std::string message;  // why not, when not written
};

// The axis labels of energy and torque: with the configured units (e.g.
// "energy [N mm]", "torque dE/dA [N mm/rad]"), else in words.
struct PlotLabels {
  std::string energy, torque;
};
PlotLabels plot_labels(const UnitNames& units);

// Draws `csv` (the deployment table) into `png`, atomically (a temporary
// name in the same directory, then renamed), its axes labelled with `units`.
PlotOutcome plot_deployment(const std::filesystem::path& csv, const std::filesystem::path& png,
                            const UnitNames& units = {});

}  // namespace xshell
