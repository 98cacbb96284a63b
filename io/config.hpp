// The configuration of a run (`xshell relax CONFIG.json`): a JSON object read
// into the plain struct Config below. Every key, its default and its unit is
// documented at its field; this header is the source of the README's table.
//
// Units: the model has none of its own, so use one consistent system. Lengths
// are in the unit of the linkage file; stresses (young_modulus, strength) in
// force per length^2, density in mass per length^3, gravity in length per
// time^2, forces in the force unit. With a linkage in millimetres: N, MPa
// (= N/mm^2), tonne/mm^3 (steel: 7.85e-9) and mm/s^2 (9810).
//
// Reading is strict: unknown keys (with the closest valid key suggested),
// wrong types, missing required keys, out-of-range or non-finite values and
// malformed JSON each throw one InputError naming the file and the key's JSON
// path (e.g. "material.cross_section.width", "supports[2].vertex"). Vertex
// indices are checked against the linkage later, by check_vertices.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "linkage/graph.hpp"
#include "linkage/graph_transform.hpp"
#include "linkage/rod_linkage.hpp"
#include "unit_names.hpp"

namespace xshell {

// "rest_shape": the rods' stress-free shape, RestShape of the model
// (linkage/rod_linkage.hpp): "input" (the rods as drawn in the linkage file
// are unstressed) or "straight" (every rod is straight and untwisted at rest).

// "joints": how a joint's rotation enters the unknowns.
enum class JointModel {
  Rotation,     // "rotation": a rotation of the joint's frame
  EdgeVectors,  // "edge_vectors": the edge vectors of the rods at the joint
};

// "material.cross_section.shape": SectionShape of the model
// (rod/material.hpp), "rectangle" or "ellipse".

// "solver.method".
enum class SolverMethod {
  Newton,          // "newton": Newton's method on the equilibrium equations
  Dynamics,        // "dynamics": damped dynamics integrated to rest
  KineticDamping,  // "kinetic-damping": dynamic relaxation, velocities zeroed at energy peaks
};

// "solver.line_search" (newton): what the backtracking along a Newton step
// watches.
enum class LineSearchSetting {
  Energy,  // "energy": Armijo backtracking on the total energy (default)
  Kinsol,  // "kinsol": KINSOL's own line search on 1/2 |scaled gradient|^2
};

// "solver.mass" (dynamics; kinetic damping always uses fictitious masses).
enum class MassSetting {
  Physical,    // "physical": the rods' mass from density and cross-section
  Fictitious,  // "fictitious": a mass chosen for the fastest stable relaxation
};

// "solver.start" (dynamics, second order): the initial velocity.
enum class StartSetting {
  SlowManifold,  // "slow_manifold": the overdamped velocity, without the initial layer (default)
  Rest,          // "rest": v = 0
};

// "output.format" of the VTK files.
enum class OutputFormat { Binary /* "binary" */, Ascii /* "ascii" */ };
// "output.compression" of the binary VTK files.
enum class OutputCompression { Lz4 /* "lz4" */, Zlib /* "zlib" */, None /* "none" */ };

// A switch that may be left to the program: true, false or "auto".
enum class Toggle { Off /* false */, On /* true */, Auto /* "auto" */ };

// An entry of "supports[].fix": what a support holds in place.
enum class Fixed {
  Position,      // "position": the joint's position (x, y and z)
  X,             // "x": one component of the position
  Y,             // "y"
  Z,             // "z"
  Orientation,   // "orientation": the joint's rotation
  OpeningAngle,  // "opening_angle": the angle between the joint's two rods
};

// "material.cross_section" (every rod's, unless "rods" overrides it).
struct CrossSectionConfig {
  SectionShape shape = SectionShape::Rectangle;  // "shape", default "rectangle"
  double width = 0;                              // "width", > 0, required; length
  double height = 0;                             // "height", > 0, required; length
};

// "material".
struct MaterialConfig {
  double young_modulus = 0;          // "young_modulus", > 0, required; stress
  double poisson_ratio = 0.3;        // "poisson_ratio", in (-1, 0.5), default 0.3
  double density = 0;                // "density", >= 0, default 0; mass / length^3
  std::optional<double> strength;    // "strength", > 0, optional; stress, for utilisation reports
  CrossSectionConfig cross_section;  // "cross_section", required
};

// "supports[].select": the vertices a support holds, instead of one "vertex".
// One of:
//   "boundary": the outer rim of the linkage and its free rod ends
//     (boundary_vertices, linkage/graph_boundary.hpp);
//   {"valence": [1, 2]}: every vertex of these valences (1 to 4);
//   {"region": {"z_max": 10.0}}: every vertex in a box of the transformed input
//     (keys x_min, x_max, y_min, y_max, z_min, z_max, at least one; bounds
//     included; length);
//   [v, ...]: these vertices (0-based, no repeats).
// Resolved against the linkage by resolve_supports (support_selection.hpp);
// selecting nothing is an error naming the entry.
enum class SelectKind { Boundary, Valence, Region, Vertices };
struct SupportSelect {
  SelectKind kind = SelectKind::Vertices;
  std::vector<int> valences;                                          // Valence
  Eigen::Vector3d region_min = Eigen::Vector3d::Constant(-HUGE_VAL);  // Region: absent bounds
  Eigen::Vector3d region_max = Eigen::Vector3d::Constant(HUGE_VAL);   // are infinite
  std::vector<int> vertices;                                          // Vertices
};

// An element of "supports" (default: none). A vertex may appear in several
// elements, but not two that hold the same position component at different
// displacements.
struct Support {
  int vertex = 0;          // "vertex", >= 0; 0-based index into the linkage file. Exactly one of
                           // "vertex" and "select" is required
  std::vector<Fixed> fix;  // "fix", required: non-empty, no duplicates
  Eigen::Vector3d displacement =
      Eigen::Vector3d::Zero();  // "displacement", [dx, dy, dz],
                                // default [0, 0, 0]; length: the held position moves to input +
                                // displacement. A non-zero component must be held by "position" or
                                // by its roller "x", "y", "z" (rejected otherwise)
  std::optional<SupportSelect> select =
      std::nullopt;  // "select" (then "vertex" is absent and unused)
};

// Where supports a and b hold a common vertex: the first position component
// both hold at different displacements (0, 1, 2), or -1 when none.
int conflicting_component(const Support& a, const Support& b);

// An element of "rods" (default: none): a material and section for some full
// rods, overriding the top-level "material". Exactly one selector:
//   "rod": k, a full rod as the topology numbers them (the rod_id cell data of
//     rods_*.vtp / stresses.vtp, the `rod` of summary.json's stresses);
//   "edges": [[i, j], ...], graph edges by their two vertices (either order):
//     the full rods that contain them (the whole rod, not only that segment);
//   "vertices": [v, ...], every full rod through (or ending at) these vertices.
// "material" takes the keys of the top-level "material", each optional and
// inherited from it (in "cross_section" too, key by key). Where entries select
// the same rod, the later entry wins.
enum class RodSelector { Rod, Edges, Vertices };
struct RodMaterial {
  RodSelector selector = RodSelector::Rod;
  int rod = 0;                            // "rod", >= 0
  std::vector<std::array<int, 2>> edges;  // "edges": non-empty, vertex indices >= 0, no repeats
  std::vector<int> vertices;              // "vertices": non-empty, >= 0, no repeats
  MaterialConfig material;                // "material", required; stored resolved (inherited
                                          // keys filled in)
};

// An element of "loads.forces".
struct PointForce {
  int vertex = 0;                                   // "vertex", >= 0, required
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // "force", [fx, fy, fz], required; force
};

// An element of "loads.line_loads": a dead load per unit of rest length.
struct LineLoadConfig {
  std::vector<int> rods;  // "rods", required: "all" (stored empty) or [k, ...], rod indices
                          // >= 0 (the rod_id of the outputs), no repeats
  Eigen::Vector3d force_per_length = Eigen::Vector3d::Zero();  // "force_per_length",
                                                               // [fx, fy, fz], required;
                                                               // force / length
};

// "loads".
struct Loads {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // "gravity", [gx, gy, gz], default
                                                      // [0, 0, 0]; length / time^2
  std::vector<PointForce> forces;                     // "forces", default none
  std::vector<LineLoadConfig> line_loads;             // "line_loads", default none
};

// "solver".
struct SolverOptions {
  SolverMethod method = SolverMethod::Newton;  // "method", default "newton"
  double gradient_tolerance = 1e-6;  // "gradient_tolerance", > 0, default 1e-6; dimensionless
  int max_iterations = 300;          // "max_iterations", >= 1, default 300 (newton)
  LineSearchSetting line_search = LineSearchSetting::Energy;  // "line_search", default "energy"
  MassSetting mass = MassSetting::Physical;                   // "mass", default "physical"
  std::optional<double> damping;  // "damping", >= 0 or "auto" (nullopt, the default);
                                  // 1 / time
  bool first_order = false;       // "first_order", default false: integrate the
                                  // first-order (gradient flow) system instead
  StartSetting start = StartSetting::SlowManifold;  // "start", default "slow_manifold"
  std::optional<int> max_steps;  // "max_steps", >= 1: time steps (dynamics) or leapfrog
                                 // iterations (kinetic-damping); default: step_limit()
  // max_steps, or its default for the method: 5000 time steps of damped
  // dynamics, 1000000 leapfrog iterations of kinetic damping.
  // "escape_saddles", default true: a converged equilibrium that is a saddle
  // (negative curvature) is left downhill along its lowest mode until a
  // stable one is reached; false reports the saddle itself.
  bool escape_saddles = true;
  // "buckling_direction", [x, y, z] not zero, default [0, 0, 1]: the side a
  // symmetric (e.g. flat) linkage leaves its symmetric state by: escapes
  // are signed so that the joints' mean displacement along it is positive.
  Eigen::Vector3d buckling_direction = Eigen::Vector3d::UnitZ();
  int step_limit() const {
    return max_steps.value_or(method == SolverMethod::KineticDamping ? 1000000 : 5000);
  }
};

// "output".
struct OutputOptions {
  std::string directory;  // "directory", default "out"; relative to the configuration
                          // file's folder, stored resolved
  int every = 1;          // "every", >= 1, default 1: write every n-th iteration or step
  int max_steps = 1000;   // "max_steps", 0 (no limit) or >= 2, default 1000: VTK steps kept;
                          // beyond, every other is removed and `every` doubles
  OutputFormat format = OutputFormat::Binary;              // "format", default "binary"
  OutputCompression compression = OutputCompression::Lz4;  // "compression", default "lz4"
  Toggle solids = Toggle::Auto;    // "solids", default "auto": also write the rods as solids
  Toggle progress = Toggle::Auto;  // "progress", default "auto": a progress display (auto:
                                   // when the output is a terminal)
};

// "analysis": the stability analysis of a converged state (the engineering
// results' lowest_eigenvalues and buckling_load_factor).
struct AnalysisOptions {
  int modes = 6;         // "modes", >= 0, default 6: eigenpairs computed
  bool buckling = true;  // "buckling", default true: the buckling load factor (under loads)
  // "max_seconds", > 0 or null (no limit), default 300: the analysis' time
  // budget; what it has not finished then is reported "time_limit".
  std::optional<double> max_seconds = 300.0;
};

// An element of "deployment.joint_angles".
struct JointAngle {
  int vertex = 0;    // "vertex", >= 0, required
  double angle = 0;  // "angle", in (0, pi), required; radians
};

// "deployment", optional: open the linkage to a target in `steps` steps. The
// object holds exactly one of "average_opening_angle" and "joint_angles".
enum class DeploymentTarget { AverageOpeningAngle, JointAngles };
struct Deployment {
  DeploymentTarget target = DeploymentTarget::AverageOpeningAngle;
  double average_opening_angle = 0;      // "average_opening_angle", in (0, pi); radians
  std::vector<JointAngle> joint_angles;  // "joint_angles": non-empty, one entry per vertex
  int steps = 20;                        // "steps", >= 1, default 20
  // "largest_step", > 0, radians, optional: adaptive increments that grow
  // from 1 / steps of the way up to this change of the actuated angle
  // (DeploymentPlan::largest_step); absent: `steps` equal increments.
  double largest_step = 0;
};

// "design.weights": the objective's terms, each >= 0, at least one > 0.
// Every term is made unit-free before it is weighted (integrators/design/
// design_scales.hpp): the fit by (targets x bounding-box diagonal d^2 / 2),
// the energies by the energy of bending every lath to a radius d, and the
// regularization is the mean squared relative change of the rest lengths.
struct DesignWeightsConfig {
  double fit = 1.0;              // "fit", default 1
  double deployed_energy = 0.0;  // "deployed_energy", default 0
  double flat_energy = 0.0;      // "flat_energy", default 0
  double regularization = 0.0;   // "regularization", default 0
};

// "design", read by `xshell design` (the inverse design, docs/model.md
// section 9.7; README, "Design"): the deployed shape the rest lengths are
// fitted to, how the objective's terms are weighted, and how far the
// optimizer may go. `xshell relax` ignores it. Exactly one
// of "target_joints" and "target_surface".
struct DesignConfig {
  double average_opening_angle = 0;  // "average_opening_angle", in (0, pi), required; radians
  std::string target_joints;    // "target_joints": {"positions": [[x, y, z] or null, ...]}, per
                                // OBJ vertex (io/target_joints_file.hpp), in the linkage file's
                                // coordinates (before "transform"); stored resolved
  std::string target_surface;   // "target_surface": a triangle mesh OBJ (f lines) whose closest
                                // points attract every joint, in the linkage file's
                                // coordinates; stored resolved
  DesignWeightsConfig weights;  // "weights"
  double bounds = 0.2;          // "bounds", in (0, 1), default 0.2: the largest relative change
                                // of each rest length
  int max_iterations = 100;     // "max_iterations", >= 1, default 100: design iterations
  int steps = 10;               // "steps", >= 1, default 10: deployment steps from the flat
                                // state to the deployed angle (once, at the start)
  Toggle flat_planar = Toggle::Auto;  // "flat_planar", default "auto" (true when every vertex
                                      // of the input has the same z): the flat state is solved
                                      // with every joint held in that plane (z)
};

struct Config {
  std::string source;        // the configuration's file name (for messages; not a key)
  std::string linkage;       // "linkage", required: the OBJ line mesh, relative to the
                             // configuration file's folder, stored resolved
  GraphTransform transform;  // "transform", default none: {"mirror": "x" | "y" | "z",
                             // "scale": > 0, "rotate_deg": [rx, ry, rz], "translate": [tx, ty,
                             // tz]}, each optional, applied to the linkage before anything else
                             // in that order (linkage/graph_transform.hpp); scale also converts
                             // the linkage's length unit
  int subdivisions = 8;      // "subdivisions", >= 3, default 8: rod edges per graph edge
  RestShape rest_shape = RestShape::Input;  // "rest_shape", default "input"
  std::vector<double> rest_lengths;  // "rest_lengths", default none (stored empty): [L_0, ...],
                                     // each > 0; length (after any "transform"): one rest length
                                     // per segment, in the linkage file's edge order ("l a b c"
                                     // gives the edges a-b, b-c), measured joint to joint,
                                     // overriding the drawing's; with either rest shape. The
                                     // count is checked against the linkage by
                                     // make_problem_setup (problem_setup.hpp)
  JointModel joints = JointModel::Rotation;  // "joints", default "rotation"
  MaterialConfig material;                   // "material", required
  std::vector<RodMaterial> rods;             // "rods", default none: per-rod materials
  std::vector<Support> supports;             // "supports", default none
  Loads loads;                               // "loads"
  SolverOptions solver;                      // "solver"
  OutputOptions output;                      // "output"
  AnalysisOptions analysis;                  // "analysis"
  std::optional<Deployment> deployment;      // "deployment", optional
  std::optional<DesignConfig> design;        // "design", optional (xshell design)
  UnitNames units;  // "units", default none: {"length": "mm", "force": "N"}, each optional, 1 to
                    // 16 characters without spaces, "/", "^", "[" or "]": the names of the
                    // system the numbers are in, for labels only (colour bars of `xshell
                    // render`, deployment.png); nothing is converted
};

// Reads the configuration file at `path` (a regular file of at most
// kMaxConfigurationFileBytes, see input_file.hpp); relative paths in it are
// resolved against the file's folder. Throws InputError.
Config read_config(const std::string& path);

// Parses configuration `text`; `name` stands for the file in messages and
// relative paths are joined to `base_dir` (left as they are when it is empty).
Config parse_config(const std::string& text, const std::string& name, const std::string& base_dir);

// Checks every vertex index of `config` against `graph` (supports, forces,
// deployment, the vertices and edges of "rods"); throws InputError naming the
// key (e.g. "supports[2].vertex") of the first out of range.
void check_vertices(const Config& config, const LineGraph& graph);

// The resolved configuration with every default filled in, in the file's
// format (absent optional keys are left out): parse_config of its dump gives
// the same configuration back.
nlohmann::json to_json(const Config& config);

}  // namespace xshell
