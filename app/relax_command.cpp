#include "relax_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <thread>
#include <utility>

#include "deploy_run.hpp"
#include "engineering_outputs.hpp"
#include "exit_status.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/stability/branch_bias.hpp"
#include "io/config.hpp"
#include "io/fabrication_file.hpp"
#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/output_error.hpp"
#include "io/problem_setup.hpp"
#include "io/state_file.hpp"
#include "io/summary_file.hpp"
#include "io/vtk/linkage_snapshot.hpp"
#include "io/vtk/vtk_series.hpp"
#include "linkage/model_error.hpp"
#include "linkage/opening_angle_range.hpp"
#include "linkage/rigid_motions.hpp"
#include "output_folder.hpp"
#include "run_warnings.hpp"
#include "solver_runs.hpp"

namespace xshell {

namespace {

namespace fs = std::filesystem;

SolverMethod parse_method(const std::string& name) {
  if (name == "newton") return SolverMethod::Newton;
  if (name == "dynamics") return SolverMethod::Dynamics;
  if (name == "kinetic-damping") return SolverMethod::KineticDamping;
  throw InputError("--solver: unknown solver \"" + name +
                   "\" (choose newton, dynamics or kinetic-damping)");
}

// Combinations the configuration can name but this version does not run:
// refuse them clearly rather than ignore them.
void check_available(const Config& config) {
  // Before any state is read: a state of rotation joints read into
  // edge-vector joints would otherwise be reported as the problem.
  if (config.deployment && config.joints != JointModel::Rotation)
    throw InputError(config.source +
                     ": deployment: needs \"joints\": \"rotation\" (edge-vector joints have no "
                     "opening-angle unknown to drive)");
  if (config.solver.method == SolverMethod::KineticDamping && config.deployment)
    throw InputError(config.source +
                     ": deployment: not available with solver.method \"kinetic-damping\"; use "
                     "\"newton\" or \"dynamics\"");
}

const char* method_name(SolverMethod m) {
  switch (m) {
    case SolverMethod::Newton:
      return "newton";
    case SolverMethod::Dynamics:
      return "dynamics";
    case SolverMethod::KineticDamping:
      return "kinetic-damping";
  }
  return "unknown";
}

// Writes every output of a run; remembers the first output error so that
// solver callbacks never throw.
class Outputs {
 public:
  Outputs(const fs::path& dir, const Config& config, const LinkageProblem& problem,
          const Eigen::Vector3d& origin)
      : dir_(dir), problem_(problem), origin_(origin) {
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

  // A step of the run; force for the first and final states.
  void step(double time, bool force) {
    if (failed() || (!force && time == last_time_)) return;
    if (force && time == last_time_) return;  // already written
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
        std::cerr << "xshell: warning: the VTK series reached its " << max_steps_
                  << " steps (output.max_steps): every other step removed, 1 in "
                  << series_->every() << " written from now on\n";
      }
    } catch (const OutputError& e) {
      error_ = e.what();  // names the file
    } catch (const std::exception& e) {
      error_ = "cannot write the VTK step " + std::to_string(series_->steps_written()) + " in '" +
               printable(dir_.string()) + "': " + e.what();
    }
  }

  void finish(const RunSummary& summary) {
    try {
      series_->close();
      write_state((dir_ / "state.json").string(), problem_.linkage(), origin_);
      write_summary((dir_ / "summary.json").string(), summary);
    } catch (const std::exception& e) {
      if (!failed()) error_ = e.what();
    }
  }

  // From another thread, while the solver still runs (a signal's grace
  // period is over): writes the state of the last written VTK step and a
  // summary `started` completed as interrupted, `reason` its reason.
  // Returns false when no step was written yet.
  bool save_last_written(RunSummary started, const std::string& reason) {
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
      write_summary((dir_ / "summary.json").string(), started);
    } catch (const std::exception& e) {
      std::cerr << "xshell: error: " << e.what() << "\n";
      return false;
    }
    return true;
  }

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  fs::path dir_;
  const LinkageProblem& problem_;
  Eigen::Vector3d origin_;
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
  int warned_thinnings_ = 0;
  std::string error_;
};

bool progress_enabled(const RelaxArguments& args, const Config& config) {
  if (args.quiet) return false;
  if (args.verbose || config.output.progress == Toggle::On) return true;
  if (config.output.progress == Toggle::Off) return false;
  return isatty(STDERR_FILENO) != 0;
}

// A run from its configuration: what load() reads and builds.
struct Run {
  Config config;
  std::optional<LinkageProblem> problem;
  ProblemSetup setup;
  int default_support = -1;              // the vertex pinned by default, or -1
  std::vector<FarSupport> far_supports;  // given supports that start far from where they hold
  std::vector<std::string> warnings;     // said on stderr, kept for the summary
};

// Says a warning on stderr and keeps it for the summary.
void warn(Run& run, const std::string& text) {
  std::cerr << "xshell: warning: " << text << "\n";
  run.warnings.push_back(text);
}

// The model holds one support per selected vertex, in the order of the
// configuration's entries: `far` names them by their entry (supports[i]).
void name_by_entry(const std::vector<std::vector<int>>& support_vertices,
                   std::vector<FarSupport>& far) {
  std::vector<int> entry_of;
  for (std::size_t i = 0; i < support_vertices.size(); ++i)
    entry_of.insert(entry_of.end(), support_vertices[i].size(), static_cast<int>(i));
  for (FarSupport& f : far)
    if (f.index < static_cast<int>(entry_of.size())) f.index = entry_of[f.index];
}

// Reads the configuration, the linkage and the state to start from, and
// builds the problem. Returns 0, or the exit status after saying why not.
int load(const RelaxArguments& args, Run& run) {
  Config& config = run.config;
  try {
    config = read_config(args.config);
    if (args.solver) config.solver.method = parse_method(*args.solver);
    if (args.out) config.output.directory = fs::absolute(*args.out).string();
    check_available(config);
    // No input may be a file the run writes into its folder.
    const fs::path out = config.output.directory;
    for (const auto& [path, what] :
         {std::pair<std::string, std::string>{args.config, "the configuration"},
          {config.linkage, "the linkage"},
          {args.init.value_or(""), "the --init state"}})
      if (!path.empty())
        if (const std::string collision = input_collision(path, what, out); !collision.empty())
          throw InputError(collision);
    const LineGraph graph = read_obj(config.linkage);
    run.setup = make_problem_setup(config, graph);
    RodLinkage linkage(run.setup.graph, run.setup.options);
    if (args.init) read_state(*args.init, linkage, run.setup.origin);
    run.problem.emplace(std::move(linkage), run.setup.statics);
    run.default_support = run.problem->default_support_vertex();
    // Before the deployment's problem, made again from this one's state.
    run.far_supports = far_supports(*run.problem, run.setup.statics.supports.size());
    name_by_entry(run.setup.support_vertices, run.far_supports);
    prepare_deployment(config, run.problem, run.setup.statics);  // no-op without "deployment"
  } catch (const InputError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitInvalidInput;
  } catch (const ModelError& e) {
    std::cerr << "xshell: error: " << (config.linkage.empty() ? args.config : config.linkage)
              << ": " << e.what() << "\n";
    return kExitInvalidInput;
  }
  return 0;
}

// Rigid motions that no support holds.
struct FreeMotions {
  std::string description;   // empty when the supports hold every rigid motion
  bool translation = false;  // a translation among them
};

// Says which vertex is pinned by default, and warns of rigid motions that
// no support holds: they make Newton's system singular unless the loads
// hold them (said again in the reason of a failure).
FreeMotions check_supports(const RelaxArguments& args, Run& run) {
  if (run.default_support >= 0)
    std::cerr << "xshell: no supports given: pinning position and orientation of vertex "
              << run.default_support << " (the joint nearest the centre)\n";
  const StaticsSetup& statics = run.setup.statics;
  const std::vector<RigidMotion> rigid_motions =
      statics.supports.empty()
          ? std::vector<RigidMotion>()
          : free_rigid_motions(statics.supports, run.problem->vertex_positions());
  FreeMotions motions;
  motions.description = describe(rigid_motions, run.setup.origin);
  // Dead loads never hold a translation: the Hessian is then singular, and
  // no equilibrium is stable, whatever a factorization said at round-off.
  motions.translation =
      std::any_of(rigid_motions.begin(), rigid_motions.end(),
                  [](const RigidMotion& m) { return m.kind == RigidMotion::Kind::Translation; });
  if (!motions.description.empty())
    warn(run, "the supports leave rigid motions free (" + motions.description +
                  "): only the loads can hold them");
  for (const FarSupport& far : run.far_supports)
    warn(run, far_support_warning(far, args.init.has_value()));
  return motions;
}

// The summary's fields known before the solve.
RunSummary start_summary(const Run& run) {
  RunSummary summary;
  summary.solver = method_name(run.config.solver.method);
  summary.unknowns = run.problem->linkage().num_dofs();
  summary.free_unknowns = run.problem->num_free();
  summary.gradient_tolerance = run.config.solver.gradient_tolerance;
  if (run.default_support >= 0) summary.default_support = run.default_support;
  summary.support_vertices = run.setup.support_vertices;
  summary.transform = run.config.transform;
  summary.configuration = to_json(run.config);
  summary.version = XSHELL_VERSION;
  summary.warnings = run.warnings;
  return summary;
}

// Runs the deployment or the solver, recording into the summary's history
// and the outputs. The solvers stop on a signal (`stop`) or an output failure.
SolverRun solve(Run& run, bool progress, const std::atomic<bool>& stop, Outputs& outputs,
                RunSummary& summary) {
  std::atomic<bool> halt{false};
  RunHooks hooks;
  hooks.snapshot = [&](double time, bool force) { outputs.step(time, force); };
  hooks.poll = [&] {
    if (stop.load() || outputs.failed()) halt = true;
  };
  hooks.stop = &halt;
  hooks.history = &summary.history;
  hooks.progress = progress;
  hooks.warn = [&](const std::string& text) {
    warn(run, text);
    summary.warnings.push_back(text);
  };
  if (run.config.deployment)
    return run_deployment(run.config, *run.problem, run.config.output.directory, hooks);
  LinkageObjective objective(*run.problem);
  return run_solver(run.config, objective, hooks,
                    branch_bias(*run.problem, run.config.solver.buckling_direction));
}

// The range of the final state's opening angles, and a warning for the
// joints outside (0, pi).
void record_opening_range(Run& run, RunSummary& summary) {
  const OpeningAngleRange range = opening_angle_range(summary.opening_angles);
  summary.min_opening_angle = range.min;
  summary.max_opening_angle = range.max;
  summary.joints_outside_opening_range = range.outside;
  if (range.outside.empty()) return;
  warn(run, opening_range_warning(range));
  summary.warnings.push_back(run.warnings.back());
}

// The summary's status of a run that its own outputs stopped (extends the
// solvers' statuses, integrators/common/solve_result.hpp).
constexpr const char* kOutputFailed = "output_failed";

// The summary's fields from what the solve found, and the final state.
// `output_error`: why the outputs stopped the run (empty if they did not).
void record_result(const SolverRun& solved, bool interrupted, const std::string& output_error,
                   const FreeMotions& motions, Run& run, RunSummary& summary) {
  const SolveResult& result = solved.result;
  summary.status = to_string(result.status);
  summary.reason = result.reason;
  summary.converged = result.converged();
  // Stability is a property of an equilibrium: of a converged state only.
  if (summary.converged) summary.stable = result.stable;
  summary.iterations = result.iterations;
  summary.gradient_norm = result.gradient_measure;
  summary.simulated_time = solved.simulated_time;
  summary.deployment = solved.deployment;
  for (const SaddleRecord& saddle : result.saddles_escaped)
    summary.saddles_escaped.push_back(
        {saddle.energy, saddle.lowest_eigenvalue,
         saddle.step >= 0 ? std::optional<int>(saddle.step) : std::nullopt});
  if (interrupted) {
    summary.status = to_string(SolveStatus::Interrupted);
    summary.reason = "interrupted by a signal";
  } else if (result.status == SolveStatus::Interrupted && !output_error.empty()) {
    // The stop flag raised by a failed output, not by a signal.
    summary.status = kOutputFailed;
    summary.reason = "stopped: an output could not be written: " + output_error;
  } else if (!summary.converged && !motions.description.empty()) {
    summary.reason = "singular system: the supports leave rigid motions free (" +
                     motions.description + "); " + summary.reason;
  } else if (!summary.converged) {
    // Supports moved far in one jump before the solve are the likeliest
    // cause: name them before what the solver saw.
    summary.reason = far_supports_reason(run.far_supports) + summary.reason;
  }
  if (motions.translation && summary.stable) summary.stable = false;
  for (char& c : summary.reason)  // one line, whatever a library said
    if (c == '\n' || c == '\r') c = ' ';
  summary.interrupted = interrupted;
  summary.energy = run.problem->energy();
  summary.vertices = run.problem->vertex_positions();
  for (auto& v : summary.vertices) v += run.setup.origin;
  summary.opening_angles = run.problem->opening_angles();
  record_opening_range(run, summary);
}

// Writes the engineering results (of a converged run whose outputs have not
// failed), the state and the summary, then the fabrication data. Returns
// the first output failure (empty: none); later outputs are still tried so
// that the state and the summary are written whenever they can be.
std::string write_final_outputs(Run& run, const SolverRun& solved, Outputs& outputs,
                                RunSummary& summary, std::chrono::steady_clock::time_point start) {
  const fs::path dir = run.config.output.directory;
  std::string error = outputs.failed() ? outputs.error() : solved.output_error;
  const bool complete = summary.converged && !summary.interrupted && error.empty();
  if (complete) {
    try {
      write_engineering_results(*run.problem, run.config, run.setup.origin, dir, summary);
    } catch (const OutputError& e) {
      error = e.what();
    } catch (const std::exception& e) {
      warn(run, std::string("no engineering results: ") + e.what());
      summary.warnings.push_back(run.warnings.back());
    }
  }
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outputs.finish(summary);
  if (error.empty() && outputs.failed()) error = outputs.error();
  if (complete && error.empty()) {
    try {
      write_fabrication(run.problem->linkage(), fabrication_units(run.config), dir);
    } catch (const OutputError& e) {
      error = e.what();
    }
  }
  return error;
}

// Writes the outputs and prints the last line. Returns the exit status.
int finish(Run& run, const SolverRun& solved, Outputs& outputs, RunSummary& summary,
           std::chrono::steady_clock::time_point start) {
  const fs::path dir = run.config.output.directory;
  const std::string error = write_final_outputs(run, solved, outputs, summary, start);
  if (!error.empty()) {
    std::cerr << "xshell: error: " << error << "\n";
    return kExitOutputFailed;
  }
  std::fprintf(stderr,
               "xshell: %s after %ld %s: %s; energy %.10e, gradient %.3e (tolerance %.1e), %s; "
               "outputs in %s\n",
               summary.status.c_str(), summary.iterations,
               run.config.solver.method == SolverMethod::Dynamics ? "steps" : "iterations",
               summary.reason.c_str(), summary.energy.total(), summary.gradient_norm,
               summary.gradient_tolerance,
               !summary.stable   ? "stability not checked (not converged)"
               : *summary.stable ? "stable"
                                 : "NOT stable (a saddle or a mechanism)",
               dir.string().c_str());
  if (summary.interrupted) return kExitInterrupted;
  return summary.converged ? kExitConverged : kExitNotConverged;
}

// Runs beside the solve until `solved`: once `stop` has been raised for
// `grace` seconds without the solve returning (one iteration of a large
// linkage can take minutes), saves the last written step's state and a
// summary, and ends the program with status 130 at once.
void watch_grace(double grace, const std::atomic<bool>& stop, const std::atomic<bool>& solved,
                 RunSummary started, Outputs& outputs) {
  using Clock = std::chrono::steady_clock;
  std::optional<Clock::time_point> raised;
  while (!solved.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (!stop.load()) continue;
    if (!raised) raised = Clock::now();
    if (std::chrono::duration<double>(Clock::now() - *raised).count() < grace) continue;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", grace);
    const std::string reason = std::string("interrupted by a signal: the iteration in progress ") +
                               "did not end within the grace period (" + seconds +
                               " s); the state is that of the last written VTK step";
    const bool saved = outputs.save_last_written(std::move(started), reason);
    std::fprintf(stderr, "xshell: interrupted: %s%s\n", reason.c_str(),
                 saved ? "" : " (none was written: no state saved)");
    std::fflush(stderr);
    std::_Exit(kExitInterrupted);  // the folder's lock goes with the process
  }
}

}  // namespace

int run_relax(const RelaxArguments& args, const std::atomic<bool>& stop) {
  const auto start = std::chrono::steady_clock::now();
  Run run;
  if (const int status = load(args, run); status != 0) return status;
  // One writer per folder, and none of an earlier run's files left behind.
  std::optional<OutputFolderLock> lock;
  std::optional<Outputs> outputs;
  try {
    lock.emplace(run.config.output.directory);
    remove_stale_outputs(run.config.output.directory);
  } catch (const OutputError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitOutputFailed;
  }
  try {
    outputs.emplace(run.config.output.directory, run.config, *run.problem, run.setup.origin);
  } catch (const std::exception& e) {
    std::cerr << "xshell: error: cannot write the output directory: " << e.what() << "\n";
    return kExitOutputFailed;
  }
  const FreeMotions motions = check_supports(args, run);
  RunSummary summary = start_summary(run);
  std::atomic<bool> solved_flag{false};
  std::thread watchdog(watch_grace, args.grace, std::cref(stop), std::cref(solved_flag),
                       start_summary(run), std::ref(*outputs));
  const SolverRun solved = solve(run, progress_enabled(args, run.config), stop, *outputs, summary);
  solved_flag = true;
  watchdog.join();
  const bool interrupted = solved.result.status == SolveStatus::Interrupted && stop.load();
  const std::string output_error = outputs->failed() ? outputs->error() : solved.output_error;
  record_result(solved, interrupted, output_error, motions, run, summary);
  return finish(run, solved, *outputs, summary, start);
}

}  // namespace xshell
