// A rod linkage (docs/model.md sections 2-7): every graph edge is a segment, a
// discrete elastic rod of n_s edges; the joints (valence 2-4 vertices) glue
// segments into full rods and pin two rods together (joint.hpp).
//
// Discretization of a segment: its terminal edge at a joint is the joint's
// edge e_X (times the segment's sign), centred on the joint, so a segment
// between two joints reaches half an edge past each of them and its n_s
// edges are as long as the joints' terminal edges allow (l_X is the smallest
// L / (n_s - k/2) over the segments of rod X at the joint, k the segment's
// number of joint ends and clamped free ends); a free end's node sits on its
// graph vertex, except at a clamped free end (LinkageOptions::clamped_ends),
// whose end edge is centred on the vertex like a terminal edge on a joint
// (docs/model.md sections 3.2, 8.2), so that the clamp acts at the vertex. The two
// segments of a rod that meet at a joint both own the shared terminal edge,
// so each gets half its stretching stiffness and half its mass (the
// reference implementation does the same): a straight rod cut into segments
// has the energy of the uncut rod. A clamped end edge also counts half (the
// half outside the rod has no mass). Minimum n_s: 3 (a segment between two
// joints needs one edge that no joint controls).
//
// Rest shape:
//  - Input: the input is stress-free. With the joints' terminal edges and
//    normals in place, each segment's frame is the least-twisted one between
//    its end frames (twist-free transport, thetas interpolated linearly in
//    arc length between the two joints' values) and rest lengths, rest
//    curvatures and rest twists are taken from that state.
//  - Straight: every rod is straight and untwisted at rest (zero rest
//    curvature and twist), rest lengths from the input, as laths cut straight
//    from stock; the flat assembly then stores bending.
//
// Reduced unknowns, in this order (docs/model.md section 6.1):
//   for each segment in edge order: its free nodes (x, y, z of the first,
//     then the next, ...: all nodes but the two of a terminal edge at a
//     joint), then its free thetas (all but a joint's terminal edge);
//   then for each joint in vertex order its 9 parameters: p (3), omega (3),
//     alpha, l_A, l_B for rotation joints, p (3), c_A (3), c_B (3) (the edge
//     vectors in fixed per-rod bases) for edge-vector joints (LinkageOptions::joint_kind,
//     joint.hpp).
// Energy = sum of the segments' energies; its gradient and Hessian follow by the chain rule through
// the joints, including the second-derivative terms of the joint-controlled node positions and
// thetas (docs/model.md sections 7.1-7.5).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "graph.hpp"
#include "joint.hpp"
#include "rod/elastic_rod.hpp"
#include "topology.hpp"

namespace xshell {

// Index of a segment's terminal edge at its end `side` (0: first, 1: last).
inline int terminal_edge_index(const ElasticRod& rod, int side) {
  return side == 0 ? 0 : rod.num_edges() - 1;
}

enum class RestShape { Input, Straight };

struct LinkageOptions {
  int subdivisions = 8;  // n_s, edges per segment (>= 3)
  RestShape rest_shape = RestShape::Input;
  JointKind joint_kind = JointKind::Rotation;  // joint parametrization (joint.hpp)
  Material material;
  // Per segment (graph edge order): each segment's own material and section
  // (mixed sections); empty: `material` for every segment. Stiffness,
  // masses, stresses and utilisation of a segment all follow its entry.
  std::vector<Material> segment_materials;
  // Free rod ends (valence-1 vertices) that a support clamps, sorted
  // (docs/model.md section 8.2): each one's end edge is centred on its vertex,
  // its nodes half an edge before and after it along the segment, and carries
  // half the edge's stretching stiffness and mass. A LinkageProblem's supports
  // must clamp exactly these ends (clamped_free_ends, statics_problem.hpp).
  std::vector<int> clamped_ends;
  // Per segment (graph edge order): its rest length (segment_rest_lengths()
  // below), overriding the drawing's; empty: the drawing's. Every edge of the
  // segment's rod is scaled by the same factor (docs/model.md section 3.8).
  std::vector<double> segment_rest_lengths;
};

constexpr int kMinSubdivisions = 3;

// Everything that, with the linkage's graph and options, reproduces a state
// exactly (restarts).
struct SegmentState {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<double> thetas;
  std::vector<SourceFrame> source_frames;
  std::vector<double> twist_hints;
};
struct JointState {
  JointKind kind = JointKind::Rotation;  // what params and reference_frame mean
  JointParams params = JointParams::Zero();
  Eigen::Matrix3d reference_frame = Eigen::Matrix3d::Identity();
};
struct LinkageState {
  std::vector<SegmentState> segments;
  std::vector<JointState> joints;
};

class RodLinkage {
 public:
  // Throws ModelError when the graph cannot be built into a linkage.
  RodLinkage(const LineGraph& graph, const LinkageOptions& options);

  const LineGraph& graph() const { return graph_; }
  const LinkageOptions& options() const { return options_; }
  const LinkageTopology& topology() const { return topology_; }
  int num_segments() const { return static_cast<int>(rods_.size()); }
  int num_joints() const { return static_cast<int>(joints_.size()); }
  const ElasticRod& segment(int s) const { return rods_[s]; }
  // Material and section of segment s.
  const Material& segment_material(int s) const {
    return options_.segment_materials.empty() ? options_.material : options_.segment_materials[s];
  }
  const Joint& joint(int j) const { return joints_[j]; }
  // Rest length of each segment (graph edge order): the sum of its edges'
  // rest lengths weighted by their stretching shares, so that a segment
  // between two joints measures joint to joint (docs/model.md section 3.8).
  std::vector<double> segment_rest_lengths() const;
  // Scales the rest lengths of each segment's edges by one factor so that
  // its rest length becomes lengths[s]; rest curvatures and twists are kept.
  // Loads that depend on the rest lengths (dead loads, masses) must be set
  // up again. Throws ModelError for a wrong count, or a length that is not
  // positive and finite.
  void set_segment_rest_lengths(const std::vector<double>& lengths);
  // Partial derivatives with respect to the segment rest lengths p (at fixed
  // reduced unknowns; rest_length_derivatives.cpp, docs/model.md section
  // 9.7): dE/dp of the elastic energy (num_segments()), and the mixed
  // derivative d(grad E)/dp of gradient() (num_dofs() x num_segments(),
  // column s nonzero only on segment s's local unknowns).
  Eigen::VectorXd energy_rest_length_derivative() const;
  Eigen::SparseMatrix<double> gradient_rest_length_derivative() const;

  // Reduced unknowns.
  int num_dofs() const { return num_dofs_; }
  int segment_dof_offset(int s) const { return segment_offset_[s]; }
  int joint_dof_offset(int j) const { return joint_offset_[j]; }
  // Reduced index of a segment's full variable, or -1 when a joint controls it.
  int reduced_index(int s, int full) const { return slots_[s][full] >= 0 ? slots_[s][full] : -1; }
  Eigen::VectorXd dofs() const;
  // Throws std::domain_error for a degenerate configuration (a terminal edge
  // of zero length, edge vectors of an edge-vector joint within
  // kMinEdgeVectorAngleDegrees of parallel).
  // With energy, also the elastic energy at the new configuration, in the
  // same pass over the segments (while each one is in cache).
  void set_dofs(const Eigen::VectorXd& dofs, RodEnergy* energy = nullptr);
  // The nodes of every segment, [segment][node], as set_dofs(dofs) would
  // place them (a joint's terminal nodes by its parameters in `dofs`),
  // without changing the state or updating a frame. Throws as set_dofs.
  std::vector<std::vector<Eigen::Vector3d>> nodes_at(const Eigen::VectorXd& dofs) const;

  LinkageState state() const;
  // Full variables of every segment in the input configuration (as built),
  // the reference of the loads' potential; restores do not change it.
  const std::vector<Eigen::VectorXd>& input_segment_dofs() const { return input_segment_dofs_; }
  // Throws std::invalid_argument when the state does not fit this linkage.
  // Joints saved in the other parametrization are converted
  // (edge_vector_conversion.hpp).
  void restore(const LinkageState& state);

  // Re-expressions of the unknowns that move nothing (see the solvers).
  void update_source_frames();
  void fold_joints();
  // Re-expresses joint j around its current geometry
  // (Joint::align_reference_frame): edge-vector joints get c_X = (l_X, 0, 0).
  void align_joint(int j) { joints_[j].align_reference_frame(); }

  // Elastic energy.
  RodEnergy energy() const;
  // Gradient and Hessian of the elastic energy minus the work of constant
  // forces on the full variables (one vector per segment, each of its
  // num_dofs(); null for none): d/dr [E - sum f . v(r)].
  Eigen::VectorXd gradient(const std::vector<Eigen::VectorXd>* forces = nullptr) const;
  void hessian_triplets(std::vector<Eigen::Triplet<double>>& triplets,
                        const std::vector<Eigen::VectorXd>* forces = nullptr) const;
  Eigen::SparseMatrix<double> hessian(const std::vector<Eigen::VectorXd>* forces = nullptr) const;

  // Diagonal of the pulled-back lumped mass matrix, diag(J^T M J) (at
  // density 1 with unit_density).
  Eigen::VectorXd lumped_mass(bool unit_density = false) const;
  // Velocity of segment s's full variables for a velocity of the reduced
  // unknowns: J v.
  Eigen::VectorXd full_velocity(int s, const Eigen::VectorXd& reduced_velocity) const;
  // The same for several (the columns): the segment's map formed once.
  Eigen::MatrixXd full_velocities(int s, const Eigen::MatrixXd& reduced_velocities) const;
  // Where each vertex sits: a joint's position, a free end's end node, a
  // clamped free end's end edge midpoint.
  Eigen::Vector3d vertex_position(int vertex) const;
  // A free-end vertex's place in its segment: the end node, the node after
  // it (inside the segment) and the edge between them. At a clamped end the
  // vertex is the edge's midpoint (the end node lies half an edge outside).
  struct FreeEnd {
    int segment = -1;
    bool at_start = true;  // the end is the segment's first node
    bool clamped = false;  // one of LinkageOptions::clamped_ends
    int end_node = 0;
    int next_node = 0;
    int edge = 0;
  };
  FreeEnd free_end(int vertex) const;

 private:
  // A segment's local reduced unknowns: its free ones, then the 9 of the
  // joint at its start, then those at its end (when there are joints).
  struct LocalMap {
    std::vector<int> global;                        // reduced index of each local unknown
    Eigen::MatrixXd jacobian;                       // full variables x local unknowns
    std::vector<std::pair<int, int>> joint_blocks;  // (local offset, side) per joint end
    std::array<Eigen::Matrix<double, 9, 9>, 7> hessians[2];
    std::array<int, 7> controlled[2];  // full variable of each terminal value, per side
  };
  LocalMap local_map(int s, bool with_hessians) const;
  // Numbers the reduced unknowns (slots_, the offsets, num_dofs_) in the
  // order described above.
  void number_unknowns();
  TerminalEdge<double> terminal(int s, int side) const;
  // The same for the joint's parameters q (its own, or duals of them).
  template <class T>
  TerminalEdge<T> terminal(int s, int side, const T* q) const;
  // Throws set_dofs' std::domain_error for a joint's parameters in `dofs`.
  void check_joint_params(const Eigen::VectorXd& dofs) const;
  // The full variables of segment s at the reduced `dofs`.
  Eigen::VectorXd segment_dofs_at(int s, const Eigen::VectorXd& dofs) const;
  // Keeps every terminal theta as the branch hint of set_dofs (see theta_hints_).
  void record_theta_hints();

  LineGraph graph_;
  LinkageOptions options_;
  LinkageTopology topology_;
  std::vector<ElasticRod> rods_;
  std::vector<Joint> joints_;
  int num_dofs_ = 0;
  std::vector<int> segment_offset_, joint_offset_;
  // Per segment and full variable: reduced index (>= 0), or -1 - (7 side + k)
  // for the k-th terminal value of the joint at that side.
  std::vector<std::vector<int>> slots_;
  std::vector<Eigen::VectorXd> input_segment_dofs_;
  // Per segment, the thetas of its start and end edges at the last source
  // update or restore: a joint fixes a terminal theta only up to 2 pi, and
  // set_dofs takes the branch nearest these, so that it is a function of its
  // argument alone. (Hinting with the current thetas made it depend on the
  // points visited since: a line search that tried a far point and came back
  // found the twist wound by 2 pi.)
  std::vector<std::array<double, 2>> theta_hints_;
};

template <class T>
TerminalEdge<T> RodLinkage::terminal(int s, int side, const T* q) const {
  const SegmentTopology& seg = topology_.segments[s];
  const ElasticRod& rod = rods_[s];
  const int edge = terminal_edge_index(rod, side);
  const double hint = theta_hints_.empty() ? rod.thetas()[edge] : theta_hints_[s][side];
  return joints_[seg.joint[side]].terminal_edge<T>(q, seg.label[side], seg.sign[side],
                                                   rod.source_frames()[edge], hint);
}

}  // namespace xshell
