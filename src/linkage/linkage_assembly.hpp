// Assembly of a rod linkage's gradient and Hessian into global vectors and
// a sparse matrix of fixed pattern: the one place where local derivatives
// become global ones (the chain rule itself is in rod_linkage_derivatives.cpp).
//
// Per segment s, with v its full variables (rod nodes and thetas) and r_s
// its local unknowns (its free ones, then the 9 parameters of the joint at
// each end), the chain rule of docs/model.md section 7.1 is
//   g_s = J^T dE/dv,  H_s = J^T (d2E/dv2) J + sum_k (dE/dv_k) d2v_k/dr_s^2,
// where J is the identity on free variables and a 7 x 9 joint Jacobian on
// each joint's terminal edge (two nodes and a theta). The rod Hessian is a
// band (stencils of 11 variables), so J^T H J is formed block by block, not
// as a dense product.
//
// What never changes is computed once, at construction: the pattern of the
// free Hessian (both triangles; only entries some stencil or joint can make
// nonzero, fixed unknowns dropped), and for every local entry the value slot
// it adds to. Each evaluation then
//   1. computes every segment's local gradient / Hessian in parallel
//      (thread_team.hpp, per-thread scratch: no allocation), writing the entries no
//      other segment adds to straight to their places, and the others into
//      its own range of a contribution buffer, and
//   2. sums the contributions of every shared entry in a fixed order (the
//      segments' order), also in parallel.
// So the result does not depend on the number of threads, bit for bit.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "affine_loop.hpp"
#include "joint_derivatives.hpp"
#include "rod_linkage.hpp"

namespace xshell {

class LinkageAssembly {
 public:
  LinkageAssembly() = default;
  // free_position: per reduced unknown of the linkage, its index among the
  // free unknowns, or -1 when it is fixed (its Hessian rows and columns are
  // dropped).
  LinkageAssembly(const RodLinkage& linkage, const std::vector<int>& free_position);

  // True when built for this linkage size and these free positions.
  bool matches(const RodLinkage& linkage, const std::vector<int>& free_position) const;

  // Gradient of E - sum_s forces_s . v_s with respect to all reduced
  // unknowns (linkage.num_dofs()); forces: one vector per segment (its full
  // variables) or null.
  void gradient(const RodLinkage& linkage, const std::vector<Eigen::VectorXd>* forces,
                Eigen::VectorXd& out);
  // Its Hessian restricted to the free unknowns (both triangles). `out` gets
  // pattern() the first time (or when its pattern differs) and then only
  // new values. With `gradient`, also the gradient above, from the same
  // pass (as gradient() gives it, to round-off). With hessian_axial_forces
  // (per segment, one per edge), the Hessian is Newton's mixed one: the
  // stretching's geometric stiffness, in the rods' Hessians and in the
  // joints' second-derivative terms, takes those axial forces instead of
  // the edges' own (docs/model.md section 9.8); the gradient stays exact.
  void hessian(const RodLinkage& linkage, const std::vector<Eigen::VectorXd>* forces,
               Eigen::SparseMatrix<double>& out, Eigen::VectorXd* gradient = nullptr,
               const std::vector<Eigen::VectorXd>* hessian_axial_forces = nullptr);
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }

 private:
  // length values from local[first..] to target[..] (both consecutive).
  struct CopyRun {
    int first, length;
    long target;
  };
  struct SegmentPlan {
    std::vector<int> free_full;                // full variable of each local free unknown
    std::array<int, 2> joint_local{{-1, -1}};  // local offset of each end's joint block, or -1
    std::array<std::array<int, 7>, 2>
        controlled{};  // full variable of each terminal value, per end
    std::array<std::vector<int>, 2>
        coupled_free;  // local free unknowns the rod couples to each end's values
    std::array<bool, 2> ends_coupled{
        {false, false}};      // whether the rod couples the two ends' values
    std::vector<int> global;  // reduced index of each local unknown
    // Kept local Hessian entries (column-major index), as runs of
    // consecutive entries: those that share their global entry with other
    // contributions, copied to the contribution buffer (a range starting at
    // hessian_begin, target = offset in it), and those that are alone in
    // theirs, copied straight to their value slots (target = first slot).
    std::vector<CopyRun> shared_runs;
    long hessian_begin = 0;
    std::vector<CopyRun> direct_runs;
    // Local gradient entries the same way: those of joint unknowns to the
    // gradient's contribution buffer (from gradient_begin), the others
    // straight to the gradient.
    std::vector<CopyRun> gradient_shared_runs;
    long gradient_begin = 0;
    std::vector<CopyRun> gradient_direct_runs;
    int size() const { return static_cast<int>(global.size()); }
  };
  // Per-thread work space, sized once for the largest segment and viewed
  // through maps of the right size.
  struct Scratch {
    std::vector<double> rod_gradient, rod_hessian, local_gradient, local_hessian, coupling;
    Eigen::Matrix<double, 7, 9> jacobian[2];
    Eigen::Matrix<double, Eigen::Dynamic, 7> coupling_rows;  // rows of coupled free unknowns
    TerminalEdgeDerivatives terminal[2];
  };
  using BoolMatrix = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

  // Construction steps (linkage_assembly_plan.cpp).
  // Segment s's local unknowns: free_full, controlled, joint_local, global.
  static void plan_unknowns(const RodLinkage& linkage, int s, SegmentPlan& plan);
  // Structure of the local Hessian from the rod's (rod_pattern, full
  // variables): free-free as is; a free row touching any controlled
  // variable of a joint couples to all 9 of its parameters (coupled_free);
  // joint blocks are full (their own second derivatives) and couple to each
  // other when the rod couples their terminal values (ends_coupled).
  static BoolMatrix local_pattern(const BoolMatrix& rod_pattern, SegmentPlan& plan);
  // pattern_ from the (free row, free column) of every Hessian contribution.
  void build_pattern(const std::vector<std::array<int, 2>>& contribution_entry);
  // The value slot in pattern_ of every contribution.
  std::vector<long> contribution_slots(
      const std::vector<std::array<int, 2>>& contribution_entry) const;
  // Appends local entry -> target to runs, extending the last run when both
  // follow on from it.
  static void append_run(std::vector<CopyRun>& runs, int entry, long target);
  // Hessian gather lists, in contribution order (segment order) for every
  // entry, and every segment's runs: slot per contribution (in plan order),
  // kept_entries per segment its local entries (column-major index). Reads
  // each plan's hessian_begin as its first contribution and sets it to its
  // range of the contribution buffer.
  void plan_hessian_sums(const std::vector<long>& slot,
                         const std::vector<std::vector<int>>& kept_entries);
  // The gradient likewise: an unknown of one segment alone (its interior
  // nodes and thetas) is written by that segment; a joint's, summed.
  void plan_gradient_sums();

  // Evaluation steps (linkage_assembly.cpp), all into the scratch.
  // Local gradient (and Hessian, mixed with the segment's
  // hessian_axial_forces when given) of segment s.
  void local_derivatives(const RodLinkage& linkage, int s,
                         const std::vector<Eigen::VectorXd>* forces, bool with_hessian,
                         Scratch& scratch,
                         const Eigen::VectorXd* hessian_axial_forces = nullptr) const;
  // The joint Jacobians (with_hessian: and second derivatives) of segment
  // s's terminal edges.
  void terminal_jacobians(const RodLinkage& linkage, int s, bool with_hessian,
                          Scratch& scratch) const;
  // Local gradient from the rod's (nv full variables): free variables map to
  // themselves, joint blocks get J^T g.
  static void local_gradient(const SegmentPlan& plan, int nv, Scratch& scratch);
  // Local Hessian: J^T H J by blocks, plus the joints' second derivatives.
  // Only entries in the plan's pattern are read afterwards: all free-free
  // ones, the rows of free unknowns coupled to an end, and the joint blocks
  // (the only ones accumulated, so the only ones zeroed).
  static void local_hessian(const SegmentPlan& plan, int nv, Scratch& scratch);
  // The blocks of the joint at `side`: its coupling to free unknowns, its
  // J^T H J with itself (and the other end's joint), its second
  // derivatives; its diagonal block made symmetric.
  static void add_joint_hessian(const SegmentPlan& plan, int side, int nv, Scratch& scratch);
  // target[run.target + i] = local[run.first + i] over the runs.
  static void copy_runs(const std::vector<CopyRun>& runs, const double* local, double* target);
  // By member `self` of the caller's parallel run of `members`
  // (thread_team.hpp): joint_work(j) for every joint, a barrier,
  // segment_work(s) for every segment, a barrier; each member takes the
  // same ranges at every call (affine_loop.hpp).
  template <class JointWork, class SegmentWork>
  void joints_then_segments(int self, int members, int num_joints, int num_segments,
                            JointWork&& joint_work, SegmentWork&& segment_work);
  // Copies segment `plan`'s local gradient to the contribution buffer and to
  // out (the gradient, num_dofs_).
  void store_gradient(const SegmentPlan& plan, const double* local, double* out);
  // Sums the gradient contributions into the entries of out (num_dofs_)
  // that several segments share: member `self`'s share of them, inside the
  // caller's parallel run of `members`.
  void sum_gradient(Eigen::VectorXd& out, int self, int members) const;
  void prepare_scratch();

  int num_dofs_ = -1;
  int max_rod_dofs_ = 0, max_local_ = 0;
  std::vector<int> free_position_;
  std::vector<SegmentPlan> plans_;
  Eigen::SparseMatrix<double> pattern_;
  // Gather lists: global entry k (shared_dofs_[k] of the gradient, or
  // shared_slots_[k] of the Hessian) sums contributions
  // sources[begin[k]..begin[k+1]).
  std::vector<int> shared_dofs_;
  std::vector<long> shared_slots_;
  std::vector<long> hessian_sources_begin_, hessian_sources_;
  std::vector<long> gradient_sources_begin_, gradient_sources_;
  std::vector<double> hessian_contributions_, gradient_contributions_;
  std::vector<Scratch> scratch_;
  std::vector<JointGeometryDerivatives> joint_geometry_;  // per joint, for the gradient or Hessian
  AffineLoop joint_loop_, segment_loop_;
  // The matrix hessian() wrote last (its pattern is pattern_ unless changed since).
  const Eigen::SparseMatrix<double>* last_output_ = nullptr;
  const double* last_values_ = nullptr;
};

}  // namespace xshell
