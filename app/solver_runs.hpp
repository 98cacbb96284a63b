// The solvers as `xshell relax` runs them, through one interface: for each
// method (newton, dynamics, kinetic-damping; the deployment in
// deploy_run.hpp) the configuration becomes the solver's options, the
// solver runs with callbacks that record every iteration in the summary's
// history, print the progress lines and write the VTK steps, and what it
// found comes back as the common result (integrators/common/solve_result.hpp),
// from which run_relax fills the summary in one place.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "integrators/common/objective.hpp"
#include "integrators/common/solve_result.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/newton/newton.hpp"
#include "io/config.hpp"
#include "io/summary_file.hpp"
#include "run_progress.hpp"

namespace xshell {

// What a run does besides solving.
struct RunHooks {
  std::function<void(double time, bool force)> snapshot;  // a VTK step of the current state
  std::function<void()> poll;  // after every iteration: raises *stop on a signal or an output
                               // failure
  const std::atomic<bool>* stop = nullptr;          // the solvers stop once it is raised
  std::vector<IterationRecord>* history = nullptr;  // the summary's history
  RunProgress* progress = nullptr;                  // progress on stderr (never null in a run)
  bool messages = true;  // the run's other lines on stderr (a deployment's outcome, a skipped plot)
  // Seconds the run's own outputs took (deployment.csv, deployment.png),
  // added up here: the summary's timings count them as output, not solve.
  double* output_seconds = nullptr;
  // Says a warning (without the "xshell: warning: " prefix) on stderr and
  // keeps it for the summary's warnings.
  std::function<void(const std::string&)> warn;
};

// What a run found.
struct SolverRun {
  SolveResult result;
  std::optional<double> simulated_time;         // dynamics only
  std::optional<DeploymentSummary> deployment;  // deployments only
  std::string output_error;  // an output of the run's own (deployment.csv) could not be written
  // A deployment's plot being drawn while the final outputs are written:
  // waits for it and names it in the summary's deployment (empty: none).
  std::function<void(DeploymentSummary&)> finish_plot;
  // Newton's CHOLMOD solver after the solve, the final state's Hessian
  // factorized by its stability test: the analysis goes on in it (null for
  // the other methods and the deployments).
  std::unique_ptr<CholeskySolver> factorization;
};

// The solvers' options from the configuration's "solver".
NewtonOptions newton_options(const SolverOptions& solver);
DynamicsOptions dynamics_options(const SolverOptions& solver);

// Runs config.solver.method on `objective` from its current state, with a
// VTK step of the first and of the final state (forced). branch_bias: over
// the objective's unknowns, the side saddles are left by
// (integrators/stability/branch_bias.hpp; empty: no preference).
SolverRun run_solver(const Config& config, Objective& objective, const RunHooks& hooks,
                     const Eigen::VectorXd& branch_bias = {});

// One line per reported iteration (or time step), on stderr; nested: as
// the deployment prints them, indented under its step lines.
void print_progress(const NewtonReport& report, bool nested);
void print_progress(const DynamicsReport& report, bool nested);

// A report as a progress sample of `phase`.
ProgressSample progress_sample(const NewtonReport& report, const std::string& phase);
ProgressSample progress_sample(const DynamicsReport& report, const std::string& phase);

// The history's record of a report, numbered `iteration` at `time`.
IterationRecord history_record(const NewtonReport& report, long iteration, double time);
IterationRecord history_record(const DynamicsReport& report, long iteration, double time);

// A report's number (0: the start) and time (Newton: the iteration number;
// dynamics: the simulated time).
inline long report_number(const NewtonReport& report) { return report.iteration; }
inline long report_number(const DynamicsReport& report) { return report.step; }
inline double report_time(const NewtonReport& report) { return report.iteration; }
inline double report_time(const DynamicsReport& report) { return report.time; }

}  // namespace xshell
