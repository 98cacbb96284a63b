#include "relax_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "deploy_run.hpp"
#include "engineering_outputs.hpp"
#include "exit_status.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/kinetic_damping/kinetic_damping.hpp"
#include "integrators/newton/newton.hpp"
#include "io/config.hpp"
#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/output_error.hpp"
#include "io/problem_setup.hpp"
#include "io/state_file.hpp"
#include "io/summary_file.hpp"
#include "io/vtk/linkage_snapshot.hpp"
#include "io/vtk/vtk_series.hpp"
#include "linkage/model_error.hpp"
#include "linkage/rigid_motions.hpp"

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

std::string status_name(NewtonStatus s) {
  switch (s) {
    case NewtonStatus::Converged:
      return "converged";
    case NewtonStatus::MaxIterations:
      return "max_iterations";
    case NewtonStatus::LinearSolverFailed:
      return "linear_solver_failed";
    case NewtonStatus::LineSearchFailed:
      return "line_search_failed";
    case NewtonStatus::NonFinite:
      return "non_finite";
    case NewtonStatus::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string status_name(DynamicsStatus s) {
  switch (s) {
    case DynamicsStatus::Converged:
      return "converged";
    case DynamicsStatus::MaxSteps:
      return "max_iterations";
    case DynamicsStatus::LinearSolverFailed:
      return "linear_solver_failed";
    case DynamicsStatus::IntegratorFailed:
      return "integrator_failed";
    case DynamicsStatus::NonFinite:
      return "non_finite";
    case DynamicsStatus::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string status_name(KineticDampingStatus s) {
  switch (s) {
    case KineticDampingStatus::Converged:
      return "converged";
    case KineticDampingStatus::MaxIterations:
      return "max_iterations";
    case KineticDampingStatus::InvalidConfiguration:
      return "invalid_configuration";
    case KineticDampingStatus::NonFinite:
      return "non_finite";
    case KineticDampingStatus::Interrupted:
      return "interrupted";
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
    series_.emplace(dir, options);
  }

  // A step of the run; force for the first and final states.
  void step(double time, bool force) {
    if (failed() || (!force && time == last_time_)) return;
    if (force && time == last_time_) return;  // already written
    try {
      if (series_->write(linkage_snapshot(problem_.linkage(), origin_, time), force))
        last_time_ = time;
    } catch (const std::exception& e) {
      error_ = e.what();
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

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  fs::path dir_;
  const LinkageProblem& problem_;
  Eigen::Vector3d origin_;
  std::optional<VtkSeries> series_;
  double last_time_ = -1.0;
  std::string error_;
};

bool progress_enabled(const RelaxArguments& args, const Config& config) {
  if (args.quiet) return false;
  if (args.verbose || config.output.progress == Toggle::On) return true;
  if (config.output.progress == Toggle::Off) return false;
  return isatty(STDERR_FILENO) != 0;
}

}  // namespace

int run_relax(const RelaxArguments& args, const std::atomic<bool>& stop) {
  const auto start = std::chrono::steady_clock::now();
  Config config;
  std::optional<LinkageProblem> problem;
  ProblemSetup setup;
  int default_support = -1;  // the vertex pinned by default, or -1
  try {
    config = read_config(args.config);
    if (args.solver) config.solver.method = parse_method(*args.solver);
    if (args.out) config.output.directory = fs::absolute(*args.out).string();
    check_available(config);
    const LineGraph graph = read_obj(config.linkage);
    setup = make_problem_setup(config, graph);
    RodLinkage linkage(setup.graph, setup.options);
    if (args.init) read_state(*args.init, linkage, setup.origin);
    problem.emplace(std::move(linkage), setup.statics);
    default_support = problem->default_support_vertex();
    prepare_deployment(config, problem, setup.statics);  // no-op without "deployment"
  } catch (const InputError& e) {
    std::cerr << "xshell: error: " << e.what() << "\n";
    return kExitInvalidInput;
  } catch (const ModelError& e) {
    std::cerr << "xshell: error: " << (config.linkage.empty() ? args.config : config.linkage)
              << ": " << e.what() << "\n";
    return kExitInvalidInput;
  }

  const fs::path dir = config.output.directory;
  std::optional<Outputs> outputs;
  try {
    outputs.emplace(dir, config, *problem, setup.origin);
  } catch (const std::exception& e) {
    std::cerr << "xshell: error: cannot write the output directory: " << e.what() << "\n";
    return kExitOutputFailed;
  }
  if (default_support >= 0)
    std::cerr << "xshell: no supports given: pinning position and orientation of vertex "
              << default_support << " (the joint nearest the centre)\n";
  // Rigid motions that no support holds make Newton's system singular
  // unless the loads hold them: said now, and in the reason of a failure.
  const std::vector<RigidMotion> rigid_motions =
      setup.statics.supports.empty()
          ? std::vector<RigidMotion>()
          : free_rigid_motions(setup.statics.supports, problem->vertex_positions());
  const std::string free_motions = describe(rigid_motions, setup.origin);
  // Dead loads never hold a translation: the Hessian is then singular, and
  // no equilibrium is stable, whatever a factorization said at round-off.
  const bool free_translation =
      std::any_of(rigid_motions.begin(), rigid_motions.end(),
                  [](const RigidMotion& m) { return m.kind == RigidMotion::Kind::Translation; });
  if (!free_motions.empty())
    std::cerr << "xshell: warning: the supports leave rigid motions free (" << free_motions
              << "): only the loads can hold them\n";

  const bool progress = progress_enabled(args, config);
  RunSummary summary;
  summary.solver = method_name(config.solver.method);
  summary.unknowns = problem->linkage().num_dofs();
  summary.free_unknowns = problem->num_free();
  summary.gradient_tolerance = config.solver.gradient_tolerance;
  if (default_support >= 0) summary.default_support = default_support;
  summary.configuration = to_json(config);
  summary.version = XSHELL_VERSION;

  // The solvers stop on this flag: raised by a signal or an output failure.
  std::atomic<bool> halt{false};
  auto poll = [&] {
    if (stop.load() || outputs->failed()) halt = true;
  };
  if (!config.deployment)
    outputs->step(0.0, true);  // a deployment writes its step 0 in equilibrium

  LinkageObjective objective(*problem);
  bool interrupted = false;
  std::string deployment_error;
  if (config.deployment) {
    DeploymentHooks hooks;
    hooks.snapshot = [&](double time, bool force) { outputs->step(time, force); };
    hooks.halted = [&] {
      poll();
      return halt.load();
    };
    hooks.progress = progress;
    const DeploymentRun run = run_deployment(config, *problem, dir, hooks, summary);
    interrupted = run.interrupted;
    deployment_error = run.output_error;
  } else if (config.solver.method == SolverMethod::Newton) {
    NewtonOptions options;
    options.gradient_tolerance = config.solver.gradient_tolerance;
    options.max_iterations = config.solver.max_iterations;
    options.line_search = config.solver.line_search == LineSearchSetting::Energy
                              ? LineSearch::Energy
                              : LineSearch::KinsolWithEnergyFallback;
    NewtonCallbacks callbacks;
    callbacks.stop = &halt;
    callbacks.on_iteration = [&](const NewtonReport& r) {
      summary.history.push_back({r.iteration, double(r.iteration), r.energy, r.gradient_measure,
                                 r.step_norm, 0.0, r.seconds});
      if (progress)
        std::fprintf(
            stderr,
            "newton %4d  energy %.10e  gradient %.3e  step %.3e  factorizations %ld%s  %.3f s\n",
            r.iteration, r.energy, r.gradient_measure, r.step_norm, r.factorizations,
            r.shifted ? " (shifted)" : "", r.seconds);
      if (r.iteration > 0) outputs->step(r.iteration, false);
      poll();
    };
    poll();
    const NewtonResult result = solve_newton(objective, options, callbacks);
    summary.status = status_name(result.status);
    summary.reason = result.reason;
    summary.converged = result.converged();
    summary.stable = result.stable;
    summary.iterations = result.iterations;
    summary.gradient_norm = result.gradient_measure;
    interrupted = result.status == NewtonStatus::Interrupted;
    outputs->step(result.iterations, true);
  } else if (config.solver.method == SolverMethod::KineticDamping) {
    KineticDampingOptions options;
    options.gradient_tolerance = config.solver.gradient_tolerance;
    options.max_iterations = config.solver.step_limit();
    KineticDampingCallbacks callbacks;
    callbacks.stop = &halt;
    long resets = 0;
    double seconds = 0.0;
    callbacks.on_iteration = [&](const KineticDampingReport& r) {
      resets += r.reset ? 1 : 0;
      seconds += r.seconds;
      // The history keeps the resets and every 100th iteration.
      if (r.reset || r.iteration % 100 == 0)
        summary.history.push_back({r.iteration, double(r.iteration), r.energy, r.gradient_measure,
                                   r.step_norm, r.kinetic_energy, r.seconds});
      // Thousands of iterations: a progress line every 100, and at resets of
      // the first 100.
      if (progress && (r.iteration % 100 == 0 || (r.reset && r.iteration < 100)))
        std::fprintf(
            stderr,
            "kinetic-damping %7ld  energy %.10e  kinetic %.3e  gradient %.3e  resets %ld  %.3f s\n",
            r.iteration, r.energy, r.kinetic_energy, r.gradient_measure, resets, seconds);
      // VTK steps at the resets (the kinetic-energy peaks), not at every
      // leapfrog iteration.
      if (r.reset) outputs->step(r.iteration, false);
      poll();
    };
    poll();
    const KineticDampingResult result = solve_kinetic_damping(objective, options, callbacks);
    summary.status = status_name(result.status);
    summary.reason = result.reason;
    summary.converged = result.converged();
    summary.stable = result.stable;
    summary.iterations = result.iterations;
    summary.gradient_norm = result.gradient_measure;
    interrupted = result.status == KineticDampingStatus::Interrupted;
    outputs->step(result.iterations, true);
  } else {
    DynamicsOptions options;
    options.form = config.solver.first_order ? DynamicsForm::FirstOrder : DynamicsForm::SecondOrder;
    options.mass =
        config.solver.mass == MassSetting::Fictitious ? MassModel::Fictitious : MassModel::Physical;
    options.start.velocity = config.solver.start == StartSetting::Rest
                                 ? DynamicsStart::Rest
                                 : DynamicsStart::SlowManifold;
    options.damping.coefficient = config.solver.damping.value_or(0.0);
    options.stopping.gradient_tolerance = config.solver.gradient_tolerance;
    options.stopping.max_steps = config.solver.step_limit();
    DynamicsCallbacks callbacks;
    callbacks.stop = &halt;
    callbacks.on_step = [&](const DynamicsReport& r) {
      summary.history.push_back(
          {r.step, r.time, r.energy, r.gradient_measure, r.step_size, r.kinetic_energy, 0.0});
      if (progress)
        std::fprintf(stderr,
                     "dynamics %6ld  t %.4e  dt %.3e  energy %.10e  kinetic %.3e  gradient %.3e\n",
                     r.step, r.time, r.step_size, r.energy, r.kinetic_energy, r.gradient_measure);
      if (r.step > 0) outputs->step(r.time, false);
      poll();
    };
    poll();
    const DynamicsResult result = solve_dynamics(objective, options, callbacks);
    summary.status = status_name(result.status);
    summary.reason = result.reason;
    summary.converged = result.converged();
    summary.stable = result.stable;
    summary.iterations = result.steps;
    summary.simulated_time = result.time;
    summary.gradient_norm = result.gradient_measure;
    interrupted = result.status == DynamicsStatus::Interrupted;
    outputs->step(result.time, true);
  }
  interrupted = interrupted && stop.load();
  if (interrupted) {
    summary.status = "interrupted";
    summary.reason = "interrupted by a signal";
  } else if (!summary.converged && !free_motions.empty()) {
    summary.reason = "singular system: the supports leave rigid motions free (" + free_motions +
                     "); " + summary.reason;
  }
  if (free_translation) summary.stable = false;
  for (char& c : summary.reason)  // one line, whatever a library said
    if (c == '\n' || c == '\r') c = ' ';
  summary.interrupted = interrupted;
  summary.energy = problem->energy();
  summary.vertices = problem->vertex_positions();
  for (auto& v : summary.vertices) v += setup.origin;
  summary.opening_angles = problem->opening_angles();
  if (summary.converged && !interrupted) {
    try {
      write_engineering_results(*problem, config, setup.origin, dir, summary);
    } catch (const OutputError& e) {
      std::cerr << "xshell: error: " << e.what() << "\n";
      return kExitOutputFailed;
    } catch (const std::exception& e) {
      std::cerr << "xshell: warning: no engineering results: " << e.what() << "\n";
    }
  }
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const bool failed_before_finish = outputs->failed();
  outputs->finish(summary);
  if (outputs->failed()) {
    std::cerr << "xshell: error: " << outputs->error() << "\n";
    return kExitOutputFailed;
  }
  if (!deployment_error.empty()) {
    std::cerr << "xshell: error: " << deployment_error << "\n";
    return kExitOutputFailed;
  }
  (void)failed_before_finish;

  std::fprintf(stderr,
               "xshell: %s after %ld %s: %s; energy %.10e, gradient %.3e (tolerance %.1e), %s; "
               "outputs in %s\n",
               summary.status.c_str(), summary.iterations,
               config.solver.method == SolverMethod::Dynamics ? "steps" : "iterations",
               summary.reason.c_str(), summary.energy.total(), summary.gradient_norm,
               summary.gradient_tolerance,
               summary.stable ? "stable" : "NOT stable (a saddle or a mechanism)",
               dir.string().c_str());
  if (interrupted) return kExitInterrupted;
  return summary.converged ? kExitConverged : kExitNotConverged;
}

}  // namespace xshell
