// The files a run of `xshell relax` writes as it goes and at its end: the
// VTK series (a step per iteration, thinned to output.max_steps), state.json
// and summary.json. The first output error is remembered rather than thrown,
// so that the solvers' callbacks never throw; the run then stops
// (relax_run.hpp) and reports it.
//
// A step's snapshot is taken from the problem at once; its files are
// written on a thread of their own while the solver goes on (encoding and
// compressing them cost as much as several Newton iterations on the
// designs). One step is in flight at most: the next step, the final files
// and save_last_written() wait for it, so that the files appear in the
// order of the steps and an error surfaces at the next step.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <future>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/summary_file.hpp"
#include "io/vtk/vtk_series.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

class RunOutputs {
 public:
  // Into `dir` (which exists), for `problem` whose positions are recentred
  // by `origin`. `log`: where the series' thinning is said
  // ("xshell: warning: ..."), or null.
  RunOutputs(const std::filesystem::path& dir, const Config& config, const LinkageProblem& problem,
             const Eigen::Vector3d& origin, std::ostream* log);

  // A step of the run; force for the first and final states.
  void step(double time, bool force);

  // The closed series and state.json, then summary.json (last, so that it
  // can hold the time the others took).
  void finish_series_and_state();
  void write_summary(const RunSummary& summary);

  // Wall seconds spent in step() so far (the snapshots, and waits for a
  // write still in flight; not the background writes themselves).
  double seconds() const { return seconds_; }

  // From another thread, while the solver still runs (a signal's grace
  // period is over): writes the state of the last written VTK step and a
  // summary `started` completed as interrupted, `reason` its reason.
  // Returns false when no step was written yet.
  bool save_last_written(RunSummary started, const std::string& reason);

  // Waits for the step in flight (an error it had becomes error()).
  ~RunOutputs();
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  void finish_in_flight();
  std::string step_error(const std::string& what) const;

  std::filesystem::path dir_;
  const LinkageProblem& problem_;
  Eigen::Vector3d origin_;
  std::ostream* log_;
  std::optional<VtkSeries> series_;
  double last_time_ = -1.0;
  int max_steps_ = 0;  // output.max_steps
  // The last written step: its linkage and what a summary says of it.
  struct LastWritten {
    RodLinkage linkage;
    EnergyReport energy;
    std::vector<Eigen::Vector3d> vertices;  // without the origin
    std::vector<std::optional<double>> opening_angles;
  };
  std::mutex last_written_mutex_;
  std::optional<LastWritten> last_written_;
  void write_in_background(LastWritten written, Snapshot snapshot);
  int warned_thinnings_ = 0;
  double seconds_ = 0.0;
  std::string error_;
  // The step being written (shared: save_last_written() waits for it from
  // another thread); in_flight_mutex_ guards the handle, not the write.
  std::mutex in_flight_mutex_;
  std::shared_future<void> in_flight_;
  bool closed_ = false;  // save_last_written() has begun: no more steps (in_flight_mutex_)
};

}  // namespace xshell
