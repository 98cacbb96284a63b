#include "relax_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <utility>

#include "deploy_run.hpp"
#include "engineering_outputs.hpp"
#include "exit_status.hpp"
#include "heap_settings.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/stability/branch_bias.hpp"
#include "io/fabrication_file.hpp"
#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/output_error.hpp"
#include "io/state_file.hpp"
#include "linkage/model_error.hpp"
#include "linkage/opening_angle_range.hpp"
#include "linkage/rigid_motions.hpp"
#include "output_folder.hpp"
#include "run_outputs.hpp"
#include "scoped_seconds.hpp"
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

// The folder the run writes into, or "" when it writes no file.
std::string output_directory(const LoadedRun& run) {
  return run.write_files ? run.config.output.directory : std::string();
}

// Says a warning in the log and keeps it for the summary.
void warn(LoadedRun& run, const std::string& text) {
  if (run.log) *run.log << "xshell: warning: " << text << "\n";
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

Config read_configuration(const RelaxRequest& request) {
  Config config = request.config_text
                      ? parse_config(*request.config_text, request.config, request.base_dir)
                      : read_config(request.config);
  if (request.solver) config.solver.method = parse_method(*request.solver);
  if (request.out) config.output.directory = fs::absolute(*request.out).string();
  check_available(config);
  if (!request.write_files) return config;
  // No input may be a file the run writes into its folder.
  const fs::path out = config.output.directory;
  for (const auto& [path, what] :
       {std::pair<std::string, std::string>{request.config_text ? "" : request.config,
                                            "the configuration"},
        {config.linkage, "the linkage"},
        {request.init_text ? "" : request.init.value_or(""), "the --init state"}})
    if (!path.empty())
      if (const std::string collision = input_collision(path, what, out); !collision.empty())
        throw InputError(collision);
  return config;
}

ProgressStyle progress_style(const RelaxHooks& hooks, const Config& config) {
  std::optional<ProgressStyle> asked = hooks.progress_style;
  if (!asked && hooks.progress != Toggle::Auto)
    asked = hooks.progress == Toggle::On ? ProgressStyle::Text : ProgressStyle::Off;
  return resolve_progress(asked, config.output.progress, isatty(STDERR_FILENO) != 0);
}

// Rigid motions that no support holds.
struct FreeMotions {
  std::string description;   // empty when the supports hold every rigid motion
  bool translation = false;  // a translation among them
};

// Says which vertex is pinned by default, and warns of rigid motions that
// no support holds: they make Newton's system singular unless the loads
// hold them (said again in the reason of a failure).
FreeMotions check_supports(bool from_state, LoadedRun& run) {
  if (run.default_support >= 0 && run.log)
    *run.log << "xshell: no supports given: pinning position and orientation of vertex "
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
  for (const FarSupport& far : run.far_supports) warn(run, far_support_warning(far, from_state));
  return motions;
}

// The summary's fields known before the solve.
RunSummary start_summary(const LoadedRun& run) {
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
// and the outputs (if any). The solvers stop on *hooks.stop or an output
// failure.
SolverRun solve(LoadedRun& run, const RelaxHooks& hooks, RunOutputs* outputs, RunSummary& summary,
                RunProgress& progress, double& output_seconds) {
  std::atomic<bool> halt{false};
  size_t reported = 0;  // history records passed to hooks.on_iteration
  RunHooks run_hooks;
  run_hooks.snapshot = [&](double time, bool force) {
    if (outputs) outputs->step(time, force);
  };
  run_hooks.poll = [&] {
    if (hooks.on_iteration) {
      const std::vector<IterationRecord> records(summary.history.begin() + reported,
                                                 summary.history.end());
      reported = summary.history.size();
      hooks.on_iteration(records);
    }
    if ((hooks.stop && hooks.stop->load()) || (outputs && outputs->failed())) halt = true;
  };
  run_hooks.stop = &halt;
  run_hooks.history = &summary.history;
  run_hooks.progress = &progress;
  run_hooks.output_seconds = &output_seconds;
  run_hooks.messages = hooks.log != nullptr;
  run_hooks.warn = [&](const std::string& text) {
    warn(run, text);
    summary.warnings.push_back(text);
  };
  if (run.config.deployment)
    return run_deployment(run.config, *run.problem, output_directory(run), run_hooks);
  LinkageObjective objective(*run.problem);
  return run_solver(run.config, objective, run_hooks,
                    branch_bias(*run.problem, run.config.solver.buckling_direction));
}

// The range of the final state's opening angles, and a warning for the
// joints outside (0, pi).
void record_opening_range(LoadedRun& run, RunSummary& summary) {
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
                   const FreeMotions& motions, LoadedRun& run, RunSummary& summary) {
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

// The engineering results of a complete run (converged, not interrupted, no
// output failed) into the summary, and their files into `dir` unless it is
// empty. Returns an output failure (empty: none); a failure of the
// computation is a warning.
std::string record_engineering(LoadedRun& run, const SolverRun& solved, const fs::path& dir,
                               RunSummary& summary, RunProgress& progress) {
  try {
    EngineeringSnapshot snapshot;
    {
      const ScopedSeconds timer(&summary.timings.analysis);
      snapshot = engineering_results(
          *run.problem, run.config, run.setup.origin, summary,
          [&](const StabilityProgress& p) {
            if (p.iteration == 0)
              progress.phase("analysis", p.stage);
            else
              progress.sample({"analysis", p.stage, p.iteration, p.energy, p.gradient, std::nullopt,
                               std::nullopt},
                              true);
          },
          solved.factorization.get());
    }
    const ScopedSeconds timer(&summary.timings.output);
    if (!dir.empty()) write_engineering_files(snapshot, run.config, dir);
  } catch (const OutputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    warn(run, std::string("no engineering results: ") + e.what());
    summary.warnings.push_back(run.warnings.back());
  }
  return "";
}

// Completes the summary with the engineering results (of a converged run
// whose outputs have not failed) and, with outputs, writes them, the state
// and the summary, then the fabrication data. Returns the first output
// failure (empty: none); later outputs are still tried so that the state
// and the summary are written whenever they can be.
std::string write_final_outputs(LoadedRun& run, const SolverRun& solved, RunOutputs* outputs,
                                RunSummary& summary, RunProgress& progress) {
  const fs::path dir = output_directory(run);
  std::string error = outputs && outputs->failed() ? outputs->error() : solved.output_error;
  const bool complete = summary.converged && !summary.interrupted && error.empty();
  if (complete) error = record_engineering(run, solved, dir, summary, progress);
  if (outputs) {
    progress.phase("output");
    const ScopedSeconds timer(&summary.timings.output);
    outputs->finish_series_and_state();
    if (error.empty() && outputs->failed()) error = outputs->error();
    if (complete && error.empty()) {
      try {
        write_fabrication(run.problem->linkage(), fabrication_units(run.config), dir);
      } catch (const OutputError& e) {
        error = e.what();
      }
    }
  }
  if (solved.finish_plot && summary.deployment) {
    const ScopedSeconds timer(&summary.timings.output);
    solved.finish_plot(*summary.deployment);
  }
  summary.wall_seconds = progress.elapsed();
  if (!outputs) return error;
  outputs->write_summary(summary);
  if (error.empty() && outputs->failed()) error = outputs->error();
  return error;
}

// Runs beside the solve until `solved`: once `stop` has been raised for
// `grace` seconds without the solve returning (one iteration of a large
// linkage can take minutes), saves the last written step's state and a
// summary, and ends the program with status 130 at once.
void watch_grace(double grace, const std::atomic<bool>& stop, const std::atomic<bool>& solved,
                 RunSummary started, RunOutputs& outputs) {
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

// The output folder of `run`, locked and cleared, and its outputs; none
// without a folder. Returns why they could not be opened (empty: they were).
std::string open_outputs(const LoadedRun& run, std::optional<OutputFolderLock>& lock,
                         std::optional<RunOutputs>& outputs) {
  const std::string dir = output_directory(run);
  if (dir.empty()) return "";
  // One writer per folder, and none of an earlier run's files left behind.
  try {
    lock.emplace(dir);
    remove_stale_outputs(dir);
  } catch (const OutputError& e) {
    return e.what();
  }
  try {
    outputs.emplace(dir, run.config, *run.problem, run.setup.origin, run.log);
  } catch (const std::exception& e) {
    return std::string("cannot write the output directory: ") + e.what();
  }
  return "";
}

}  // namespace

void load_run(const RelaxRequest& request, LoadedRun& run) {
  Config& config = run.config;
  try {
    ScopedSeconds load(nullptr);
    config = read_configuration(request);
    run.write_files = request.write_files;
    const LineGraph graph = read_obj(config.linkage);
    run.load_seconds = load.elapsed();
    const ScopedSeconds setup(&run.setup_seconds);
    run.setup = make_problem_setup(config, graph);
    RodLinkage linkage(run.setup.graph, run.setup.options);
    if (request.init_text)
      restore_state(*request.init_text, request.init.value_or("the state"), linkage,
                    run.setup.origin);
    else if (request.init)
      read_state(*request.init, linkage, run.setup.origin);
    run.problem.emplace(std::move(linkage), run.setup.statics);
    run.default_support = run.problem->default_support_vertex();
    // Before the deployment's problem, made again from this one's state.
    run.far_supports = far_supports(*run.problem, run.setup.statics.supports.size());
    name_by_entry(run.setup.support_vertices, run.far_supports);
    prepare_deployment(config, run.problem, run.setup.statics);  // no-op without "deployment"
  } catch (const ModelError& e) {
    throw InputError((config.linkage.empty() ? request.config : config.linkage) + ": " + e.what());
  }
}

namespace {

// The exit status of a run that solved: its outputs failed, it was
// interrupted, or it converged or not.
int relax_exit_status(const std::string& output_error, const RunSummary& summary) {
  if (!output_error.empty()) return kExitOutputFailed;
  if (summary.interrupted) return kExitInterrupted;
  return summary.converged ? kExitConverged : kExitNotConverged;
}

}  // namespace

RelaxOutcome relax(const RelaxRequest& request, const RelaxHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  keep_freed_heap();
  RelaxOutcome outcome;
  LoadedRun run;
  run.log = hooks.log;
  try {
    load_run(request, run);
  } catch (const InputError& e) {
    outcome.exit_status = kExitInvalidInput;
    outcome.error = e.what();
    return outcome;
  }
  RunProgress progress(progress_style(hooks, run.config), start);
  outcome.directory = output_directory(run);
  std::optional<OutputFolderLock> lock;
  std::optional<RunOutputs> outputs;
  {
    const ScopedSeconds timer(&run.setup_seconds);
    outcome.error = open_outputs(run, lock, outputs);
  }
  if (!outcome.error.empty()) {
    outcome.exit_status = kExitOutputFailed;
    return outcome;
  }
  RunOutputs* out = outputs ? &*outputs : nullptr;
  const FreeMotions motions = check_supports(request.init || request.init_text, run);
  RunSummary summary = start_summary(run);
  summary.timings.load = run.load_seconds;
  summary.timings.setup = run.setup_seconds;
  const std::atomic<bool> never{false};
  const std::atomic<bool>& stop = hooks.stop ? *hooks.stop : never;
  std::atomic<bool> solved_flag{false};
  std::optional<std::thread> watchdog;
  if (request.grace && out)
    watchdog.emplace(watch_grace, *request.grace, std::cref(stop), std::cref(solved_flag),
                     start_summary(run), std::ref(*out));
  double solve_output = 0.0;  // seconds of the outputs written during the solve
  progress.phase(run.config.deployment ? "deploy" : "solve");
  const ScopedSeconds solving(nullptr);
  const SolverRun solved = solve(run, hooks, out, summary, progress, solve_output);
  solve_output += out ? out->seconds() : 0.0;
  summary.timings.solve = std::max(0.0, solving.elapsed() - solve_output);
  summary.timings.output = solve_output;
  solved_flag = true;
  if (watchdog) watchdog->join();
  const bool interrupted = solved.result.status == SolveStatus::Interrupted && stop.load();
  const std::string output_error = out && out->failed() ? out->error() : solved.output_error;
  record_result(solved, interrupted, output_error, motions, run, summary);
  outcome.error = write_final_outputs(run, solved, out, summary, progress);
  progress.finish(summary.status, summary.timings, summary.wall_seconds);
  if (request.keep_state) outcome.state = state_text(run.problem->linkage(), run.setup.origin);
  outcome.exit_status = relax_exit_status(outcome.error, summary);
  outcome.summary = std::move(summary);
  return outcome;
}

}  // namespace xshell
