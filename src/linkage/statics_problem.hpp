// A statics problem on a rod linkage: which unknowns supports hold fixed,
// which dead loads act, and the free unknowns the solvers move.
//
// Supports act on graph vertices. At a joint: "position" fixes p (or one component for a roller).
// Rotation joints: "orientation" fixes omega (the joint's bisector frame and normal; the opening
// angle stays free), "opening_angle" fixes alpha. Edge-vector joints: "orientation" makes the joint
// the constrained joint of docs/model.md section 8.1: the joint is re-expressed around its current
// directions (Joint::align_reference_frame, c_X = (l_X, 0, 0)) and the deviations c_A[1..2],
// c_B[1..2] are fixed, so both directions (hence also the normal and the opening angle) are held
// and only the two lengths stay free; "opening_angle" is refused (no such unknown). At a free rod
// end: "position" fixes the end node (or components), "orientation" clamps the end: it fixes the
// end edge's two nodes and its theta (direction, length and twist of the end edge). A clamped end
// edge is centred on its vertex (the linkage is built so: LinkageOptions::clamped_ends, which must
// list exactly the free ends that the supports clamp, clamped_free_ends below), so the clamp acts
// at the vertex (docs/model.md section 8.2). Without any
// support, the joint nearest the bounding-box centre (ties: lowest index) has its position and
// orientation fixed, which removes exactly the rigid motions (for an edge-vector joint, also that
// joint's opening).
//
// Loads: gravity g acts on lumped node masses (density x area x the node's
// share of rest length, terminal edges at joints counted half by each of
// their two segments); a line load w (force per unit rest length) on the
// chosen rods is lumped the same way (w x the node's share of rest length,
// docs/model.md section 4.8); point forces on a vertex (a joint's p or a free end's
// node; at a clamped free end half on each node of the clamped edge, so that
// it acts at the vertex). Potential of the loads: -sum f . (x - x_input); the
// total energy includes it.
//
// Convergence measure: with L the diagonal of the input's bounding box,
// EI_max the largest bending stiffness of any segment and F_c = EI_max / L^2, the gradient's
// force components (positions, lengths, edge vectors) divided by F_c and its
// moment components (thetas, omega, alpha) by L F_c; the solve has converged when
// the largest is at most the dimensionless gradient tolerance. That measure
// is the same in any unit system.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <vector>

#include "linkage_assembly.hpp"
#include "rod_linkage.hpp"

namespace xshell {

enum class SupportDof { Position, X, Y, Z, Orientation, OpeningAngle };

// A prescribed support displacement (settlement, a pushed boundary) moves
// the held position components of the vertex to input + displacement: a
// joint's p, or a free end's node (where "orientation" clamps that end, both
// nodes of the clamped edge by the same amount: the clamped edge translates). Only
// components held by Position / X / Y / Z may be displaced (ModelError
// otherwise). The constructor sets the fixed unknowns to the displaced
// values, so every solve starts from them; reactions are then those at the
// displaced state. "input" is the linkage as built from its graph, whatever
// state the linkage is in when the problem is made (a restart from a saved
// state included; zero displacement too): the held positions depend on the
// supports alone, and making the problem again from a solved state holds the
// same positions. How far that moved each support's vertex is
// LinkageProblem::support_start_offsets(). The default pin (no supports
// given) holds its joint where it is.
struct VertexSupport {
  int vertex = 0;
  std::vector<SupportDof> fix;
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // length; components that fix holds
};

struct PointLoad {
  int vertex = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

// A dead load per unit of rest length on some full rods (numbered as
// LinkageTopology::rods, the rod_id of the outputs).
struct LineLoad {
  std::vector<int> rods;                                       // empty: every rod
  Eigen::Vector3d force_per_length = Eigen::Vector3d::Zero();  // force / length
};

struct StaticsSetup {
  std::vector<VertexSupport> supports;  // none: the default pin described above
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  std::vector<PointLoad> forces;
  std::vector<LineLoad> line_loads;
};

// The free rod ends (valence-1 vertices of graph) that `supports` clamp (fix
// "orientation"), sorted: the LinkageOptions::clamped_ends of a linkage to be
// held by these supports. Vertices out of range are left out (the problem
// refuses them).
std::vector<int> clamped_free_ends(const LineGraph& graph,
                                   const std::vector<VertexSupport>& supports);

struct EnergyReport {
  double stretching = 0, bending = 0, twisting = 0, external = 0;
  double total() const { return stretching + bending + twisting + external; }
};

class LinkageProblem {
 public:
  // Throws ModelError for a support or load that does not apply, and when the
  // supports clamp other free ends than the linkage was built to clamp
  // (LinkageOptions::clamped_ends).
  LinkageProblem(RodLinkage linkage, const StaticsSetup& setup);

  const RodLinkage& linkage() const { return linkage_; }
  // The vertex pinned by default, when no support was given (else -1).
  int default_support_vertex() const { return default_support_; }

  int num_free() const { return static_cast<int>(free_.size()); }
  const std::vector<int>& free_indices() const { return free_; }
  // The position of a reduced unknown among the free ones, -1 when it is fixed.
  int free_position(int reduced_index) const { return free_position_[reduced_index]; }
  Eigen::VectorXd free_dofs() const;
  // A vector on the free unknowns (a velocity, a step, multipliers) as one on
  // all reduced unknowns, zero on the fixed ones.
  Eigen::VectorXd with_fixed_zero(const Eigen::VectorXd& q) const;
  void set_free_dofs(const Eigen::VectorXd& q);
  // The nodes of every segment, [segment][node], where set_free_dofs(q)
  // would place them, without moving there (RodLinkage::nodes_at).
  std::vector<std::vector<Eigen::Vector3d>> nodes_at(const Eigen::VectorXd& q) const {
    return linkage_.nodes_at(dofs_with_free(q));
  }
  // The same, returning energy().total() there (computed in the same pass).
  double set_free_dofs_and_energy(const Eigen::VectorXd& q);
  // All reduced unknowns (fixed ones included), e.g. for restarts.
  Eigen::VectorXd dofs() const { return linkage_.dofs(); }
  void set_dofs(const Eigen::VectorXd& r) {
    linkage_.set_dofs(r);
    ++version_;
  }

  EnergyReport energy() const;
  Eigen::VectorXd free_gradient() const;
  // Gradient of the total energy over all reduced unknowns, fixed ones
  // included: at an equilibrium, minus its fixed entries are the generalized
  // reactions of the supports (reactions.hpp).
  Eigen::VectorXd full_gradient() const;
  // Free Hessian, both triangles; its pattern never changes. Its pass also
  // yields the gradient: until the configuration (or its parametrization,
  // rebase()) changes, the gradient functions return that one, and a second
  // free_hessian() returns the same matrix without recomputing it.
  const Eigen::SparseMatrix<double>& free_hessian();
  // Forgets the cached gradient and Hessian, so that the next calls compute
  // them (benchmarks time them this way).
  void discard_cached_derivatives() { gradient_version_ = hessian_version_ = -1; }
  // Newton's mixed Hessian (docs/model.md section 9.8): from this call on,
  // free_hessian() gives the stretching's geometric stiffness the axial
  // forces linearized along the free step p from the current configuration
  // (RodLinkage::full_velocity of p, ElasticRod::linearized_axial_forces),
  // whatever configuration it is evaluated at, until use_exact_hessian().
  // The energy and gradient stay exact. A step that changes no edge by more
  // than kNegligibleEdgeChange of its rest length keeps (or makes) the
  // Hessian exact: there the two differ by at most that fraction of an
  // edge's axial stiffness (by its square at the full step), and a solve
  // converging in such a step needs the exact one for its stability test.
  void use_mixed_hessian(const Eigen::VectorXd& p);
  static constexpr double kNegligibleEdgeChange = 1e-4;
  void use_exact_hessian();
  bool mixed_hessian() const { return !hessian_axial_forces_.empty(); }
  Eigen::VectorXd gradient_weights() const;
  // max |w_i g_i| over the free unknowns.
  double gradient_measure() const;
  // Lumped masses of the free unknowns (at density 1 everywhere when some
  // segment's material has none, so that they stay positive).
  Eigen::VectorXd free_mass() const;

  // Updates the rods' source frames and folds the (rotation) joints; when
  // given, the free velocity is carried over so that it describes the same
  // motion.
  void rebase(Eigen::VectorXd* free_velocity = nullptr);

  // The supports in force (the default pin included), and whether a reduced
  // unknown is held by one.
  const std::vector<VertexSupport>& supports() const { return supports_; }
  // Per supports() entry: how far the constructor moved the vertex's held
  // position components (a joint's p, a free end's end node) from where the
  // linkage was to where the support holds them (length; zero where it
  // already was, and for the default pin).
  const std::vector<Eigen::Vector3d>& support_start_offsets() const { return start_offsets_; }
  bool is_fixed(int reduced_index) const { return fixed_[reduced_index]; }
  // Dead loads: per segment on its full variables (gravity, forces at free
  // ends), and on the reduced unknowns (forces at joints).
  const std::vector<Eigen::VectorXd>& segment_loads() const { return segment_forces_; }
  const Eigen::VectorXd& joint_loads() const { return point_forces_; }
  // The dead loads without their component along a direction (the
  // symmetric problem that the deployment's branch choice follows beside
  // this one, integrators/deployment/deployment.hpp), and back as given.
  void remove_loads_along(const Eigen::Vector3d& direction);
  void restore_loads() { scale_loads(1.0); }
  // The dead loads as given times factor (the buckling check,
  // integrators/stability/stability_analysis.hpp).
  void scale_loads(double factor);
  // Sum over the dead loads as given of f . direction (gravity, line loads
  // and point forces): negative when they push against it.
  double load_along(const Eigen::Vector3d& direction) const;

  // Sets the segment rest lengths (RodLinkage::set_segment_rest_lengths)
  // at the current configuration. Throws ModelError when the problem has
  // dead loads that depend on the rest lengths (gravity, line loads, lumped
  // on each node's share of rest length): they would keep their old values.
  void set_segment_rest_lengths(const std::vector<double>& lengths);
  // Gravity or a nonzero line load acts.
  bool has_rest_length_loads() const { return rest_length_loads_; }

  double length_scale() const { return length_scale_; }
  double force_scale() const { return force_scale_; }

  // Per graph vertex: position (joint p, free end node, clamped end edge
  // midpoint), and opening angle (nullopt for free ends).
  std::vector<Eigen::Vector3d> vertex_positions() const;
  std::vector<std::optional<double>> opening_angles() const;

 private:
  // All reduced unknowns as they are, with the free ones replaced by q.
  Eigen::VectorXd dofs_with_free(const Eigen::VectorXd& q) const;
  // The energy report of the current configuration, given its elastic part.
  EnergyReport energy_with(const RodEnergy& elastic) const;
  void fix(int index) { fixed_[index] = true; }
  // Construction steps (statics_setup.cpp): fixes the unknowns a support
  // holds, at a joint (aligning an edge-vector joint it orients) or at a
  // free rod end; sets the dead loads of setup.
  void fix_support(const VertexSupport& support);
  void fix_at_joint(int j, SupportDof dof, int vertex);
  void fix_at_free_end(int vertex, SupportDof dof);
  void set_loads(const StaticsSetup& setup);

  RodLinkage linkage_;
  std::vector<bool> fixed_;
  std::vector<int> free_;
  std::vector<VertexSupport> supports_;
  std::vector<Eigen::Vector3d> start_offsets_;  // per supports_ entry
  int default_support_ = -1;
  std::vector<Eigen::VectorXd> segment_forces_;  // dead loads on full variables
  Eigen::VectorXd point_forces_;                 // on reduced unknowns
  std::vector<char> has_segment_loads_;          // per segment: any nonzero load
  bool has_point_loads_ = false;
  bool rest_length_loads_ = false;  // gravity or line loads (lumped on rest lengths)
  std::vector<Eigen::VectorXd> given_segment_forces_;  // the loads as given
  Eigen::VectorXd given_point_forces_;
  Eigen::VectorXd input_dofs_;  // joint positions at the input (the rest is unused)
  double length_scale_ = 1.0, force_scale_ = 1.0;
  Eigen::SparseMatrix<double> hessian_;
  // Bumped by every change of the configuration or of its parametrization;
  // the full gradient and the Hessian above are those of these versions.
  long version_ = 0;
  mutable long gradient_version_ = -1;
  mutable Eigen::VectorXd gradient_;
  long hessian_version_ = -1;
  // Per segment, the axial forces of the mixed Hessian; empty: exact.
  std::vector<Eigen::VectorXd> hessian_axial_forces_;
  // Pattern, value slots and work space of free_gradient() / free_hessian(),
  // built at their first call (and again if the free unknowns change).
  mutable LinkageAssembly assembly_;
  std::vector<int> free_position_;  // reduced index -> free index or -1
};

}  // namespace xshell
