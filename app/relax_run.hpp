// One run of `xshell relax`, from a configuration to its summary, as the
// command line (relax_command.hpp) and the Python module (python/) both run
// it: read the configuration, the linkage and a state to start from, build
// the problem, solve it (or deploy it) with the configured solver, analyse
// the equilibrium, and fill the summary that summary.json holds
// (io/summary_file.hpp). With an output folder it also writes what the
// command line writes (README, "Outputs"): the VTK series as the run goes,
// then the engineering results, state.json, summary.json and the fabrication
// data. Without one it writes no file; the summary is the same, but for the
// deployment's plot (null) and the times.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/problem_setup.hpp"
#include "io/summary_file.hpp"
#include "linkage/statics_problem.hpp"
#include "run_progress.hpp"
#include "run_warnings.hpp"

namespace xshell {

// What to run.
struct RelaxRequest {
  // The configuration: the file `config`, or when `config_text` is given,
  // that JSON text, named `config` in messages, its relative paths relative
  // to `base_dir` (as they are when empty).
  std::string config;
  std::optional<std::string> config_text;
  std::string base_dir;
  std::optional<std::string> solver;  // "newton" | "dynamics" | "kinetic-damping", or the file's
  std::optional<std::string> out;     // output folder (relative to the working directory)
  bool write_files = true;            // false: no file written (the configuration's
                                      // output.directory stays in the summary, unused)
  // A state to start from: the state.json `init`, or when `init_text` is
  // given, that text, named `init` in messages.
  std::optional<std::string> init;
  std::optional<std::string> init_text;
  // Seconds an iteration may go on once *stop is raised; then the last
  // written step's state is saved and the process ends with status 130
  // (relax_command.hpp). None: the run always returns.
  std::optional<double> grace;
  bool keep_state = false;  // return the final state's text (RelaxOutcome::state)
};

// How a run reports as it goes.
struct RelaxHooks {
  const std::atomic<bool>* stop = nullptr;  // raised: the solver stops at its next iteration
  // After every iteration, with each record of the summary's history made
  // since the last call (none at the start): may raise *stop.
  std::function<void(const std::vector<IterationRecord>& records)> on_iteration;
  // Progress on stderr (run_progress.hpp): On (text lines), Off, or Auto:
  // as the configuration's output.progress says (its "auto": text lines on a
  // terminal, plain lines at a low rate without one). `progress_style`,
  // when given, is taken instead (`--progress`).
  Toggle progress = Toggle::Off;
  std::optional<ProgressStyle> progress_style;
  // "xshell: ..." lines (warnings, the default pin, a deployment's outcome), or none.
  std::ostream* log = nullptr;
};

// A configuration read and its problem built: what a run starts from.
struct LoadedRun {
  Config config;
  std::optional<LinkageProblem> problem;
  ProblemSetup setup;
  int default_support = -1;              // the vertex pinned by default, or -1
  std::vector<FarSupport> far_supports;  // given supports that start far from where they hold
  std::vector<std::string> warnings;     // said in the log, kept for the summary
  std::ostream* log = nullptr;
  bool write_files = true;     // into config.output.directory (RelaxRequest::write_files)
  double load_seconds = 0.0;   // reading the configuration and the linkage
  double setup_seconds = 0.0;  // building the model and the problem
};

// Reads the configuration, the linkage and the state to start from, and
// builds the problem (readied for the deployment when there is one). Throws
// InputError with the command line's message for any input rejected.
void load_run(const RelaxRequest& request, LoadedRun& run);

// What a run found.
struct RelaxOutcome {
  int exit_status = 0;  // the command line's (exit_status.hpp)
  // Why the run failed (kExitInvalidInput, kExitOutputFailed), as the
  // command line says it after "xshell: error: "; empty otherwise.
  std::string error;
  std::optional<RunSummary> summary;  // of a run that solved
  std::string state;                  // its final state, state.json's text (keep_state)
  std::string directory;              // its output folder (empty: none)
};

// Runs `request`. Input errors are returned (exit_status kExitInvalidInput),
// not thrown.
RelaxOutcome relax(const RelaxRequest& request, const RelaxHooks& hooks);

}  // namespace xshell
