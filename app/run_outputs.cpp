#include "run_outputs.hpp"

#include "integrators/common/solve_result.hpp"
#include "io/input_error.hpp"
#include "io/output_error.hpp"
#include "io/state_file.hpp"
#include "io/vtk/linkage_snapshot.hpp"
#include "scoped_seconds.hpp"

namespace xshell {

namespace fs = std::filesystem;

RunOutputs::RunOutputs(const fs::path& dir, const Config& config, const LinkageProblem& problem,
                       const Eigen::Vector3d& origin, std::ostream* log)
    : dir_(dir), problem_(problem), origin_(origin), log_(log) {
  SeriesOptions options;
  options.every = config.output.every;
  options.format =
      config.output.format == OutputFormat::Ascii ? VtkFormat::Ascii : VtkFormat::Binary;
  const long edges = static_cast<long>(problem.linkage().num_segments()) * config.subdivisions;
  options.solids = config.output.solids == Toggle::On ||
                   (config.output.solids == Toggle::Auto && edges <= 20000);
  options.max_steps = max_steps_ = config.output.max_steps;
  series_.emplace(dir, options);
}

void RunOutputs::step(double time, bool force) {
  if (failed() || (!force && time == last_time_)) return;
  if (force && time == last_time_) return;  // already written
  const ScopedSeconds timer(&seconds_);
  try {
    if (series_->write(linkage_snapshot(problem_.linkage(), origin_, time), force)) {
      last_time_ = time;
      // For save_last_written(), with what its summary reports: computed
      // here from the live problem, because a LinkageProblem built there
      // (its Hessian pattern included) took seconds on large linkages,
      // after the grace period (6.7 s at 1,371 joints, 10 edges per
      // segment, on a loaded machine).
      LastWritten written{problem_.linkage(), problem_.energy(), problem_.vertex_positions(),
                          problem_.opening_angles()};
      const std::lock_guard<std::mutex> lock(last_written_mutex_);
      last_written_.emplace(std::move(written));
    }
    if (series_->thinnings() > warned_thinnings_) {  // once per thinning: a few lines at most
      warned_thinnings_ = series_->thinnings();
      if (log_)
        *log_ << "xshell: warning: the VTK series reached its " << max_steps_
              << " steps (output.max_steps): every other step removed, 1 in " << series_->every()
              << " written from now on\n";
    }
  } catch (const OutputError& e) {
    error_ = e.what();  // names the file
  } catch (const std::exception& e) {
    error_ = "cannot write the VTK step " + std::to_string(series_->steps_written()) + " in '" +
             printable(dir_.string()) + "': " + e.what();
  }
}

void RunOutputs::finish_series_and_state() {
  try {
    series_->close();
    write_state((dir_ / "state.json").string(), problem_.linkage(), origin_);
  } catch (const std::exception& e) {
    if (!failed()) error_ = e.what();
  }
}

void RunOutputs::write_summary(const RunSummary& summary) {
  try {
    xshell::write_summary((dir_ / "summary.json").string(), summary);
  } catch (const std::exception& e) {
    if (!failed()) error_ = e.what();
  }
}

bool RunOutputs::save_last_written(RunSummary started, const std::string& reason) {
  const std::lock_guard<std::mutex> lock(last_written_mutex_);
  if (!last_written_) return false;
  started.status = to_string(SolveStatus::Interrupted);
  started.reason = reason;
  started.interrupted = true;
  try {
    started.energy = last_written_->energy;
    started.vertices = last_written_->vertices;
    for (auto& v : started.vertices) v += origin_;
    started.opening_angles = last_written_->opening_angles;
    write_state((dir_ / "state.json").string(), last_written_->linkage, origin_);
    xshell::write_summary((dir_ / "summary.json").string(), started);
  } catch (const std::exception& e) {
    if (log_) *log_ << "xshell: error: " << e.what() << "\n";
    return false;
  }
  return true;
}

}  // namespace xshell
