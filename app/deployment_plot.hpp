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
#include <memory>
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

// The plot of a table still being written: the constructor starts, in a
// thread of its own, the first python3 (Debian's /usr/bin/python3, else the
// one on PATH) whose script loads matplotlib at a lower priority, which
// takes about half a second, while the linkage deploys; start() then has
// it draw the complete table (or not) while the caller goes on, and
// finish() waits for it. The picture is written atomically (a temporary
// name in png's folder, then renamed). The destructor finishes without
// drawing.
class DeploymentPlotter {
 public:
  // `script`: plot_deployment.py's path, found as the header says when
  // empty.
  DeploymentPlotter(std::filesystem::path csv, std::filesystem::path png, UnitNames units = {},
                    std::filesystem::path script = {});
  ~DeploymentPlotter();
  DeploymentPlotter(const DeploymentPlotter&) = delete;
  DeploymentPlotter& operator=(const DeploymentPlotter&) = delete;

  // Has it draw `csv` into `png` when `draw`, or end; the first call
  // decides, later ones change nothing.
  void start(bool draw);
  // start(draw), then waits: the outcome (not written, no message, when not
  // asked to draw). Later calls return the same outcome.
  PlotOutcome finish(bool draw);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace xshell
