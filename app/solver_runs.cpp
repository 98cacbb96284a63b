#include "solver_runs.hpp"

#include <cstdio>
#include <string>

#include "integrators/kinetic_damping/kinetic_damping.hpp"

namespace xshell {

NewtonOptions newton_options(const SolverOptions& solver) {
  NewtonOptions o;
  o.gradient_tolerance = solver.gradient_tolerance;
  o.max_iterations = solver.max_iterations;
  o.line_search = solver.line_search == LineSearchSetting::Energy
                      ? LineSearch::Energy
                      : LineSearch::KinsolWithEnergyFallback;
  o.escape.enabled = solver.escape_saddles;
  return o;
}

DynamicsOptions dynamics_options(const SolverOptions& solver) {
  DynamicsOptions o;
  o.form = solver.first_order ? DynamicsForm::FirstOrder : DynamicsForm::SecondOrder;
  o.mass = solver.mass == MassSetting::Fictitious ? MassModel::Fictitious : MassModel::Physical;
  o.start.velocity =
      solver.start == StartSetting::Rest ? DynamicsStart::Rest : DynamicsStart::SlowManifold;
  o.damping.coefficient = solver.damping.value_or(0.0);
  o.stopping.gradient_tolerance = solver.gradient_tolerance;
  o.stopping.max_steps = solver.step_limit();
  o.escape.enabled = solver.escape_saddles;
  return o;
}

namespace {

// ", 2 chord corrections" after the factorizations, when there were any.
std::string chord_note(int corrections) {
  if (corrections == 0) return "";
  return ", " + std::to_string(corrections) +
         (corrections == 1 ? " chord correction" : " chord corrections");
}

}  // namespace

void print_progress(const NewtonReport& r, bool nested) {
  std::fprintf(
      stderr,
      "%snewton %*d  energy %.10e  gradient %.3e  step %.3e  factorizations %ld%s%s  %.3f s\n",
      nested ? "  " : "", nested ? 3 : 4, r.iteration, r.energy, r.gradient_measure, r.step_norm,
      r.factorizations, r.shifted ? " (shifted)" : "", chord_note(r.chord_corrections).c_str(),
      r.seconds);
}

void print_progress(const DynamicsReport& r, bool nested) {
  std::fprintf(stderr,
               "%sdynamics %6ld  t %.4e  dt %.3e  energy %.10e  kinetic %.3e  gradient %.3e\n",
               nested ? "  " : "", r.step, r.time, r.step_size, r.energy, r.kinetic_energy,
               r.gradient_measure);
}

ProgressSample progress_sample(const NewtonReport& r, const std::string& phase) {
  return {phase, "newton", r.iteration, r.energy, r.gradient_measure, {}, {}};
}

ProgressSample progress_sample(const DynamicsReport& r, const std::string& phase) {
  return {phase, "dynamics", r.step, r.energy, r.gradient_measure, {}, {}};
}

IterationRecord history_record(const NewtonReport& r, long iteration, double time) {
  return {iteration, time, r.energy, r.gradient_measure, r.step_norm, 0.0, r.seconds};
}

IterationRecord history_record(const DynamicsReport& r, long iteration, double time) {
  return {iteration, time, r.energy, r.gradient_measure, r.step_size, r.kinetic_energy, 0.0};
}

namespace {

// The callback of a solver's reports: each into the history, a progress
// line, a VTK step (after the start's), then the poll.
template <class Report>
std::function<void(const Report&)> record_reports(const RunHooks& hooks) {
  return [&hooks](const Report& r) {
    hooks.history->push_back(history_record(r, report_number(r), report_time(r)));
    if (hooks.progress->every_iteration()) print_progress(r, false);
    hooks.progress->sample(progress_sample(r, "solve"));
    if (report_number(r) > 0) hooks.snapshot(report_time(r), false);
    hooks.poll();
  };
}

SolverRun run_newton(const SolverOptions& solver, Objective& objective, const RunHooks& hooks,
                     const Eigen::VectorXd& branch_bias) {
  NewtonCallbacks callbacks;
  callbacks.stop = hooks.stop;
  callbacks.on_iteration = record_reports<NewtonReport>(hooks);
  hooks.poll();
  SolverRun run;
  NewtonOptions options = newton_options(solver);
  options.escape.bias = branch_bias;
  // A relaxation may start far from its equilibrium (a flat linkage, or
  // the descent from its flat saddle: the largest design's relaxation took
  // 63 iterations, 18 of them full steps at max_step; 55 with the cap
  // grown, the same equilibrium).
  options.grow_step_cap = true;
  NewtonSolver newton(objective, options);
  run.result = newton.solve(callbacks);
  run.factorization = std::make_unique<CholeskySolver>();
  newton.swap_cholesky(*run.factorization);
  return run;
}

SolverRun run_kinetic_damping(const SolverOptions& solver, Objective& objective,
                              const RunHooks& hooks) {
  KineticDampingOptions options;
  options.gradient_tolerance = solver.gradient_tolerance;
  options.max_iterations = solver.step_limit();
  KineticDampingCallbacks callbacks;
  callbacks.stop = hooks.stop;
  long resets = 0;
  double seconds = 0.0;
  constexpr long kResetSpacing = 100;
  long last_written = -kResetSpacing;  // iteration of the last reset offered as a VTK step
  callbacks.on_iteration = [&](const KineticDampingReport& r) {
    resets += r.reset ? 1 : 0;
    seconds += r.seconds;
    // The history keeps the resets and every 100th iteration.
    if (r.reset || r.iteration % 100 == 0)
      hooks.history->push_back({r.iteration, double(r.iteration), r.energy, r.gradient_measure,
                                r.step_norm, r.kinetic_energy, r.seconds});
    // Thousands of iterations: a progress line every 100, and at resets of
    // the first 100.
    hooks.progress->sample(
        {"solve", "kinetic-damping", r.iteration, r.energy, r.gradient_measure, {}, {}});
    if (hooks.progress->every_iteration() &&
        (r.iteration % 100 == 0 || (r.reset && r.iteration < 100)))
      std::fprintf(
          stderr,
          "kinetic-damping %7ld  energy %.10e  kinetic %.3e  gradient %.3e  resets %ld  %.3f s\n",
          r.iteration, r.energy, r.kinetic_energy, r.gradient_measure, resets, seconds);
    // VTK steps at the resets (the kinetic-energy peaks), not at every
    // leapfrog iteration, and at most one per kResetSpacing iterations: at
    // the round-off floor of the gradient a peak follows every few
    // iterations (the sample at a tolerance of 1e-30: 2,731 step files,
    // 89 MB, 55 of its 59 s, before it stopped on stagnation).
    if (r.reset && r.iteration - last_written >= kResetSpacing) {
      hooks.snapshot(r.iteration, false);
      last_written = r.iteration;
    }
    hooks.poll();
  };
  hooks.poll();
  SolverRun run;
  run.result = solve_kinetic_damping(objective, options, callbacks);
  return run;
}

SolverRun run_dynamics(const SolverOptions& solver, Objective& objective, const RunHooks& hooks,
                       const Eigen::VectorXd& branch_bias) {
  DynamicsCallbacks callbacks;
  callbacks.stop = hooks.stop;
  callbacks.on_step = record_reports<DynamicsReport>(hooks);
  hooks.poll();
  DynamicsOptions options = dynamics_options(solver);
  options.escape.bias = branch_bias;
  const DynamicsResult result = solve_dynamics(objective, options, callbacks);
  SolverRun run;
  run.result = result;
  run.simulated_time = result.time;
  return run;
}

}  // namespace

SolverRun run_solver(const Config& config, Objective& objective, const RunHooks& hooks,
                     const Eigen::VectorXd& branch_bias) {
  hooks.snapshot(0.0, true);
  SolverRun run;
  switch (config.solver.method) {
    case SolverMethod::Newton:
      run = run_newton(config.solver, objective, hooks, branch_bias);
      break;
    case SolverMethod::KineticDamping:
      run = run_kinetic_damping(config.solver, objective, hooks);
      break;
    case SolverMethod::Dynamics:
      run = run_dynamics(config.solver, objective, hooks, branch_bias);
      break;
  }
  // The final state: at its time, or numbered after the last iteration.
  hooks.snapshot(run.simulated_time.value_or(static_cast<double>(run.result.iterations)), true);
  return run;
}

}  // namespace xshell
