// summary.json: what a run of `xshell relax` found, for people and tools.
//
// Fields (units are those of the configuration):
//   status            "converged" | "max_iterations" | "linear_solver_failed" |
//                     "line_search_failed" | "integrator_failed" | "non_finite" | "interrupted" |
//                     "step_failed" (a deployment step failed even with halved increments) |
//                     "invalid_configuration" (kinetic damping kept leaving valid configurations) |
//                     "output_failed" (the run stopped because an output could not be written)
//   reason            one line
//   converged, interrupted   booleans
//   stable            of a converged state: an LL^T factorization of the free Hessian
//                     succeeded (a saddle is never stable); null when the run did not converge
//   solver            "newton" | "dynamics" | "kinetic-damping"
//   iterations        Newton iterations, dynamics steps or kinetic-damping (leapfrog) iterations
//   simulated_time    dynamics only
//   wall_seconds      from the start of the run to the writing of summary.json
//   timings           {load, setup, solve, analysis, output}: seconds of each phase (RunTimings)
//   unknowns, free_unknowns
//   gradient_norm     the dimensionless convergence measure (max scaled free gradient)
//   gradient_tolerance
//   energy            {total, stretching, bending, twisting, external}; external =
//                     -sum f . (x - x_input), included in total
//   vertices          per graph vertex in file order: [x, y, z] of a joint's position, a
//                     free end's end node or a clamped free end's end edge midpoint
//   opening_angles    per vertex, radians; null for free ends
//   min_opening_angle, max_opening_angle   over every joint, radians (null without joints)
//   joints_outside_opening_range   [{vertex, angle}] of the joints whose opening angle is
//                     outside (0, pi) (rods passed through each other there), by vertex
//   warnings          what the run warned of on stderr, one line each (supports that start far
//                     from where they are held, joints outside (0, pi), free rigid motions, ...)
//   default_support   the vertex pinned when no support was given, else null
//   supports          per entry of the configuration's "supports", in order: {entry (its
//                     index), vertices (the vertices it holds, increasing: its "vertex" or
//                     what its "select" selected)}
//   transform         null, or the "transform" applied to the input: {mirror, scale,
//                     rotate_deg, translate, matrix (4 x 4, rows: x_out = M [x_in; 1])}
//   saddles_escaped   the saddles the solver converged to and left downhill along negative
//                     curvature ("solver.escape_saddles"), in order: {energy (total at the
//                     saddle), lowest_eigenvalue (of H phi = lambda M phi there, 1/time^2, < 0),
//                     step (the deployment step being solved; null outside a deployment)};
//                     empty when none was met
//   history           per iteration/step: {iteration, time, energy, gradient_norm, step,
//                     kinetic_energy, seconds}; kinetic damping keeps only its resets and
//                     every 100th iteration
//   deployment        only for a run with a "deployment": {actuation ("average_opening_angle" |
//                     "joint_angles"), status ("completed" | "step_failed" | "interrupted"),
//                     steps (accepted steps after step 0, the start), failed_attempts (steps
//                     retried with half the increment), curvature_dropped (step attempts that
//                     started from the tangent's prediction, every curved one's energy
//                     being higher), round_off_floor_steps (accepted steps whose
//                     gradient measure stagnated at its round-off floor within twice the
//                     tolerance), iterations (solver iterations or time steps, all steps),
//                     factorizations (the sparse factorizations of every attempt and of the
//                     twin, where the solver counts them), chord_corrections (Newton's
//                     steps with an iteration's factorization, not counted in iterations),
//                     start_average_angle,
//                     target_average_angle (null for joint_angles), final_average_angle
//                     (radians), final_torque (dE/dA, energy per radian), table
//                     ("deployment.csv"), plot ("deployment.png" or null),
//                     branch_switch_step (the step at which the loaded branch on the side of
//                     solver.buckling_direction was taken from the unloaded twin, or null)}
//   reactions, stresses, joint_forces, lowest_eigenvalues, buckling_load_factor,
//   stability_analysis   engineering results of the final state (engineering_json.hpp)
//   configuration     the resolved configuration; version: the program's version
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "linkage/graph_transform.hpp"
#include "linkage/opening_angle_range.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

struct IterationRecord {
  long iteration = 0;
  double time = 0.0;  // simulated time (dynamics) or the iteration index (Newton)
  double energy = 0.0;
  double gradient_norm = 0.0;
  double step = 0.0;  // Newton step max-norm or time step size
  double kinetic_energy = 0.0;
  double seconds = 0.0;
};

// The "timings" object: wall seconds of the run's phases, which do not
// overlap, so that they add up to at most wall_seconds. load: reading the
// configuration and the linkage file; setup: building the model and the
// problem (and the --init state), opening the output folder; solve: the
// solver or the deployment, without the writing of its outputs; analysis:
// the engineering results of a converged state (stability, buckling);
// output: the VTK steps, deployment.csv and .png, the engineering files,
// the fabrication data, the closed series and state.json (summary.json's
// own writing, which holds these numbers, is not counted).
struct RunTimings {
  double load = 0.0, setup = 0.0, solve = 0.0, analysis = 0.0, output = 0.0;
  double total() const { return load + setup + solve + analysis + output; }
};

// An element of "saddles_escaped" (see above).
struct SaddleSummary {
  double energy = 0.0;
  double lowest_eigenvalue = 0.0;
  std::optional<int> step;
};

// The "deployment" object (see above).
struct DeploymentSummary {
  std::string actuation;  // "average_opening_angle" | "joint_angles"
  std::string status;     // "completed" | "step_failed" | "interrupted"
  int steps = 0;
  int failed_attempts = 0;
  int curvature_dropped = 0;
  int round_off_floor_steps = 0;
  long iterations = 0;
  long factorizations = 0;
  long chord_corrections = 0;
  double start_average_angle = 0.0;
  std::optional<double> target_average_angle;
  double final_average_angle = 0.0;
  double final_torque = 0.0;
  std::optional<int> branch_switch_step;
  std::string table = "deployment.csv";
  std::optional<std::string> plot;
};

struct RunSummary {
  std::string status;
  std::string reason;
  bool converged = false, interrupted = false;
  std::optional<bool> stable;  // of a converged state only: null otherwise
  std::string solver;
  long iterations = 0;
  std::optional<double> simulated_time;
  double wall_seconds = 0.0;
  RunTimings timings;
  int unknowns = 0, free_unknowns = 0;
  double gradient_norm = 0.0, gradient_tolerance = 0.0;
  EnergyReport energy;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::optional<double>> opening_angles;
  std::optional<double> min_opening_angle, max_opening_angle;
  std::vector<JointOutsideOpeningRange> joints_outside_opening_range;
  std::vector<std::string> warnings;
  std::optional<int> default_support;
  std::vector<std::vector<int>> support_vertices;  // per configuration entry
  GraphTransform transform;
  std::vector<SaddleSummary> saddles_escaped;
  std::vector<IterationRecord> history;
  std::optional<DeploymentSummary> deployment;  // runs with a "deployment" only
  nlohmann::json configuration;
  std::string version;
  // Engineering results of the final state (engineering_json()): each key
  // goes to the top level of summary.json. Empty when not computed.
  nlohmann::json engineering = nlohmann::json::object();
};

nlohmann::json to_json(const RunSummary& summary);

// Writes summary.json atomically; throws OutputError.
void write_summary(const std::string& path, const RunSummary& summary);

}  // namespace xshell
