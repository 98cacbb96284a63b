#include "design_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "design_outputs.hpp"
#include "design_targets.hpp"
#include "exit_status.hpp"
#include "heap_settings.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "integrators/design/design_scales.hpp"
#include "io/input_error.hpp"
#include "io/output_error.hpp"
#include "io/state_file.hpp"
#include "linkage/model_error.hpp"
#include "output_folder.hpp"
#include "relax_run.hpp"
#include "solver_runs.hpp"

namespace xshell {

namespace {

struct DesignSetup {
  LoadedRun run;
  DesignTargets targets;
  std::optional<LinkageProblem> planar;  // the flat problem held in its plane (flat_planar)
};

void check_design_inputs(const DesignRequest& request, const LoadedRun& run) {
  const Config& c = run.config;
  if (!c.design)
    throw InputError(c.source +
                     ": needs a \"design\" section for xshell design (README, \"Design\")");
  if (c.deployment)
    throw InputError(c.source +
                     ": deployment: xshell design deploys to design.average_opening_angle "
                     "itself; remove \"deployment\"");
  if (c.joints != JointModel::Rotation)
    throw InputError(c.source +
                     ": design: needs \"joints\": \"rotation\" (the design holds the average "
                     "opening angle)");
  if (run.problem->has_rest_length_loads())
    throw InputError(c.source +
                     ": loads: gravity and line loads are lumped on the rest lengths, and their "
                     "derivative is not modelled: xshell design needs a configuration without "
                     "them (point forces are allowed)");
  if (!request.write_files) return;
  for (const std::string& target : {c.design->target_joints, c.design->target_surface})
    if (!target.empty())
      if (const std::string collision = input_collision(target, "the target", c.output.directory);
          !collision.empty())
        throw InputError(collision);
}

// Whether every vertex of the (transformed) input lies in one plane z = const.
bool planar_in_z(const LineGraph& graph) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& x : graph.vertices) {
    lo = std::min(lo, x.z());
    hi = std::max(hi, x.z());
    box.extend(x);
  }
  return hi - lo <= 1e-9 * box.diagonal().norm();
}

// The flat problem with every vertex's z held (and the default pin made
// explicit, as supports now exist), unless a support holds it already.
LinkageProblem held_in_plane(const LoadedRun& run) {
  StaticsSetup statics = run.setup.statics;
  if (statics.supports.empty())
    statics.supports.push_back({run.problem->default_support_vertex(),
                                {SupportDof::Position, SupportDof::Orientation},
                                Eigen::Vector3d::Zero()});
  const int n = static_cast<int>(run.setup.graph.vertices.size());
  std::vector<bool> held(n, false);
  for (const VertexSupport& s : statics.supports)
    for (SupportDof d : s.fix)
      held[s.vertex] = held[s.vertex] || d == SupportDof::Position || d == SupportDof::Z;
  for (int v = 0; v < n; ++v)
    if (!held[v]) statics.supports.push_back({v, {SupportDof::Z}, Eigen::Vector3d::Zero()});
  return LinkageProblem(run.problem->linkage(), statics);
}

void load_design(const DesignRequest& request, std::ostream* log, DesignSetup& s) {
  RelaxRequest relax;
  relax.config = request.config;
  relax.config_text = request.config_text;
  relax.base_dir = request.base_dir;
  relax.out = request.out;
  relax.write_files = request.write_files;
  relax.init = request.init;
  relax.init_text = request.init_text;
  s.run.log = log;
  load_run(relax, s.run);
  check_design_inputs(request, s.run);
  const Config& c = s.run.config;
  try {
    s.targets = read_design_targets(c, s.run.problem->linkage(), s.run.setup.origin);
    const bool planar = planar_in_z(s.run.setup.graph);
    if (c.design->flat_planar == Toggle::On && !planar)
      throw InputError(c.source +
                       ": design.flat_planar: the linkage is not flat (its vertices' z differ); "
                       "a flat state can be held only in the plane z = const");
    if (c.design->flat_planar != Toggle::Off && planar) s.planar.emplace(held_in_plane(s.run));
  } catch (const ModelError& e) {
    throw InputError(c.source + ": " + e.what());
  }
}

DesignOptions design_options(const DesignSetup& s) {
  const DesignConfig& d = *s.run.config.design;
  DesignOptions o;
  o.deployed_angle = d.average_opening_angle;
  o.targets = s.targets.targets;
  o.retarget = s.targets.retarget;
  o.weights = {d.weights.fit, d.weights.deployed_energy, d.weights.flat_energy,
               d.weights.regularization};
  o.newton = newton_options(s.run.config.solver);
  o.deployment_steps = d.steps;
  return o;
}

DesignScales scales_of(const DesignObjective& objective) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& x : objective.deployed().vertex_positions()) box.extend(x);
  const double d = box.diagonal().norm();
  return design_scales(static_cast<int>(objective.targets().size()), d,
                       bending_energy_scale(objective.deployed().linkage(), d),
                       objective.num_parameters());
}

// One progress line of a history record (history_record, design_outputs.hpp).
void say_iteration(std::ostream& log, const nlohmann::json& r) {
  char line[320];
  std::snprintf(line, sizeof line,
                "xshell: design: iteration %d: objective %.6e (fit %.3e, deployed energy %.3e, "
                "flat energy %.3e, regularization %.3e); fit rms %.3e; optimality %.2e; "
                "%d evaluations (%d failed); %.1f s\n",
                r["iteration"].get<int>(), r["objective"].get<double>(), r["fit"].get<double>(),
                r["deployed_energy"].get<double>(), r["flat_energy"].get<double>(),
                r["regularization"].get<double>(), r["fit_rms"].get<double>(),
                r["optimality"].get<double>(), r["evaluations"].get<int>(),
                r["failed_evaluations"].get<int>(), r["seconds"].get<double>());
  log << line << std::flush;
}

int exit_status_of(MinimizerStatus status) {
  switch (status) {
    case MinimizerStatus::Converged:
      return kExitConverged;
    case MinimizerStatus::Interrupted:
      return kExitInterrupted;
    default:
      return kExitNotConverged;
  }
}

// The flat equilibrium of the optimized design: the objective's own when it
// solves one, else solved now (from the start's flat state).
LinkageProblem flat_result(DesignObjective& objective, const DesignSetup& s,
                           const std::vector<double>& lengths, std::string& warning) {
  if (objective.flat()) return *objective.flat();
  const LinkageProblem& start = s.planar ? *s.planar : *s.run.problem;
  HeldEquilibrium flat(start, average_opening_angle(start.linkage()), objective.options().newton);
  std::string reason;
  if (flat.solve(&lengths, reason)) return flat.problem();
  warning = "the flat equilibrium of the optimized design was not found (" + reason +
            "); the flat state written is the start's with the new rest lengths";
  LinkageProblem unsolved = start;
  unsolved.set_segment_rest_lengths(lengths);
  return unsolved;
}

DesignOutcome optimize(DesignSetup& s, const DesignHooks& hooks,
                       std::chrono::steady_clock::time_point start) {
  DesignOutcome outcome;
  const Config& c = s.run.config;
  const DesignOptions options = design_options(s);
  std::optional<DesignObjective> objective;
  try {
    if (hooks.log)
      *hooks.log << "xshell: design: deploying to " << c.design->average_opening_angle << " rad\n";
    objective.emplace(*s.run.problem, options, s.planar ? &*s.planar : nullptr);
  } catch (const ModelError& e) {
    outcome.exit_status = kExitInvalidInput;
    outcome.error = c.source + ": " + e.what();
    return outcome;
  } catch (const std::runtime_error& e) {
    outcome.exit_status = kExitNotConverged;
    outcome.error = e.what();
    return outcome;
  }
  const DesignScales scales = scales_of(*objective);
  objective->set_weights(scaled_weights(options.weights, scales));
  DesignLoopOptions loop;
  loop.max_relative_change = c.design->bounds;
  loop.max_iterations = c.design->max_iterations;
  loop.stop = hooks.stop;
  const int targets = static_cast<int>(objective->targets().size());
  loop.on_iteration = [&](const DesignIteration& it) {
    const nlohmann::json record = history_record(it, scales, targets);
    if (hooks.log) say_iteration(*hooks.log, record);
    if (hooks.on_iteration) hooks.on_iteration(it, record);
  };
  const DesignLoopResult result = optimize_design(*objective, loop);
  std::string warning;
  const LinkageProblem flat = flat_result(*objective, s, result.lengths, warning);
  if (!warning.empty() && hooks.log) *hooks.log << "xshell: warning: " << warning << "\n";
  DesignReport report{result, scales, *objective, flat, s.planar.has_value(), warning};
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.report = design_report_json(report, c);
  outcome.deployed_state = state_text(objective->deployed().linkage(), s.run.setup.origin);
  outcome.flat_state = state_text(flat.linkage(), s.run.setup.origin);
  outcome.exit_status = exit_status_of(result.status);
  if (!s.run.write_files) return outcome;
  try {
    write_design_outputs(report, c, s.run.setup.origin, *outcome.report, outcome.deployed_state,
                         outcome.flat_state);
  } catch (const OutputError& e) {
    outcome.exit_status = kExitOutputFailed;
    outcome.error = e.what();
  }
  return outcome;
}

}  // namespace

DesignOutcome run_design(const DesignRequest& request, const DesignHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  keep_freed_heap();
  DesignSetup setup;
  try {
    load_design(request, hooks.log, setup);
  } catch (const InputError& e) {
    DesignOutcome outcome;
    outcome.exit_status = kExitInvalidInput;
    outcome.error = e.what();
    return outcome;
  }
  std::optional<OutputFolderLock> lock;
  const std::string dir = setup.run.write_files ? setup.run.config.output.directory : "";
  if (!dir.empty()) {
    try {
      lock.emplace(dir);
      remove_stale_outputs(dir);
    } catch (const OutputError& e) {
      DesignOutcome outcome;
      outcome.exit_status = kExitOutputFailed;
      outcome.error = e.what();
      return outcome;
    }
  }
  DesignOutcome outcome = optimize(setup, hooks, start);
  outcome.directory = dir;
  return outcome;
}

}  // namespace xshell
