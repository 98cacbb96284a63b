#include "run_outputs.hpp"

#include "integrators/common/solve_result.hpp"
#include "io/input_error.hpp"
#include "io/output_error.hpp"
#include "io/state_file.hpp"
#include "io/vtk/linkage_snapshot.hpp"
#include "scoped_seconds.hpp"
#include "vtk_write_options.hpp"

namespace xshell {

namespace fs = std::filesystem;

RunOutputs::RunOutputs(const fs::path& dir, const Config& config, const LinkageProblem& problem,
                       const Eigen::Vector3d& origin, std::ostream* log)
    : dir_(dir), problem_(problem), origin_(origin), log_(log) {
  SeriesOptions options;
  options.every = config.output.every;
  const WriteOptions encoding = vtk_write_options(config.output);
  options.format = encoding.format;
  options.compression = encoding.compression;
  const long edges = static_cast<long>(problem.linkage().num_segments()) * config.subdivisions;
  options.solids = config.output.solids == Toggle::On ||
                   (config.output.solids == Toggle::Auto && edges <= 20000);
  options.max_steps = max_steps_ = config.output.max_steps;
  series_.emplace(dir, options);
}

RunOutputs::~RunOutputs() { finish_in_flight(); }

// An error of the step being written that names no file.
std::string RunOutputs::step_error(const std::string& what) const {
  return "cannot write the VTK step " + std::to_string(series_->steps_written()) + " in '" +
         printable(dir_.string()) + "': " + what;
}

void RunOutputs::step(double time, bool force) {
  if (failed() || (!force && time == last_time_)) return;
  if (force && time == last_time_) return;  // already written
  const ScopedSeconds timer(&seconds_);
  finish_in_flight();
  if (failed()) return;
  try {
    if (!series_->due(force)) return;
    Snapshot snapshot = linkage_snapshot(problem_.linkage(), origin_, time);
    last_time_ = time;
    // For save_last_written(), with what its summary reports: computed
    // here from the live problem, because a LinkageProblem built there
    // (its Hessian pattern included) took seconds on large linkages,
    // after the grace period (6.7 s at 1,371 joints, 10 edges per
    // segment, on a loaded machine).
    LastWritten written{problem_.linkage(), problem_.energy(), problem_.vertex_positions(),
                        problem_.opening_angles()};
    write_in_background(std::move(written), std::move(snapshot));
  } catch (const std::exception& e) {
    error_ = step_error(e.what());
  }
}

// Under in_flight_mutex_, so that save_last_written() sees either the step
// recorded and its write in flight (and waits for it) or neither: once it
// has begun (closed_), a step is dropped, and no file is being written when
// the program ends.
void RunOutputs::write_in_background(LastWritten written, Snapshot snapshot) {
  const std::lock_guard<std::mutex> lock(in_flight_mutex_);
  if (closed_) return;
  {
    const std::lock_guard<std::mutex> last(last_written_mutex_);
    last_written_.emplace(std::move(written));
  }
  in_flight_ = std::async(std::launch::async, [this, snapshot = std::move(snapshot)] {
                 series_->write_now(snapshot);
               }).share();
}

// Waits for the step in flight; its error becomes error(), and a thinning
// of the series it made is said (here, on the solver's thread).
void RunOutputs::finish_in_flight() {
  std::shared_future<void> job;
  {
    const std::lock_guard<std::mutex> lock(in_flight_mutex_);
    job = in_flight_;
  }
  if (!job.valid()) return;
  job.wait();
  {
    const std::lock_guard<std::mutex> lock(in_flight_mutex_);
    in_flight_ = {};
  }
  try {
    job.get();
  } catch (const OutputError& e) {
    if (!failed()) error_ = e.what();  // names the file
  } catch (const std::exception& e) {
    if (!failed()) error_ = step_error(e.what());
  }
  if (series_->thinnings() > warned_thinnings_) {  // once per thinning: a few lines at most
    warned_thinnings_ = series_->thinnings();
    if (log_)
      *log_ << "xshell: warning: the VTK series reached its " << max_steps_
            << " steps (output.max_steps): every other step removed, 1 in " << series_->every()
            << " written from now on\n";
  }
}

void RunOutputs::finish_series_and_state() {
  finish_in_flight();
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
  std::shared_future<void> job;
  {
    const std::lock_guard<std::mutex> lock(in_flight_mutex_);
    closed_ = true;  // no step is started from now on
    job = in_flight_;
  }
  if (job.valid()) job.wait();  // the last written step's files are complete
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
