#include "linkage_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "segment_parallel.hpp"
#include "thread_team.hpp"

namespace xshell {

namespace {

// Joints are taken by pairs: one costs about a microsecond, a segment
// several.
constexpr int kJointChunk = 2;

}  // namespace

void LinkageAssembly::copy_runs(const std::vector<CopyRun>& runs, const double* local,
                                double* target) {
  for (const CopyRun& run : runs)
    for (int i = 0; i < run.length; ++i) target[run.target + i] = local[run.first + i];
}

void LinkageAssembly::store_gradient(const SegmentPlan& plan, const double* local, double* out) {
  copy_runs(plan.gradient_shared_runs, local, gradient_contributions_.data() + plan.gradient_begin);
  copy_runs(plan.gradient_direct_runs, local, out);
}

template <class JointWork, class SegmentWork>
void LinkageAssembly::joints_then_segments(int self, int members, int num_joints, int num_segments,
                                           JointWork&& joint_work, SegmentWork&& segment_work) {
  if (self == 0) {
    joint_loop_.reset(num_joints, members);
    segment_loop_.reset(num_segments, members);
  }
  ThreadTeam::barrier();
  joint_loop_.run(self, kJointChunk, joint_work);
  ThreadTeam::barrier();
  segment_loop_.run(self, 1, segment_work);
  ThreadTeam::barrier();
}

void LinkageAssembly::prepare_scratch() {
  if (static_cast<int>(scratch_.size()) >= assembly_threads()) return;
  scratch_.resize(assembly_threads());
  for (Scratch& w : scratch_) {
    w.rod_gradient.resize(max_rod_dofs_);
    w.rod_hessian.resize(static_cast<size_t>(max_rod_dofs_) * max_rod_dofs_);
    w.local_gradient.resize(max_local_);
    w.local_hessian.resize(static_cast<size_t>(max_local_) * max_local_);
    w.coupling_rows.resize(max_local_, 7);
  }
}

void LinkageAssembly::local_derivatives(const RodLinkage& linkage, int s,
                                        const std::vector<Eigen::VectorXd>* forces,
                                        bool with_hessian, Scratch& w,
                                        const Eigen::VectorXd* hessian_axial_forces) const {
  const ElasticRod& rod = linkage.segment(s);
  const SegmentPlan& plan = plans_[s];
  const int nv = rod.num_dofs();
  Eigen::Map<Eigen::VectorXd> gv(w.rod_gradient.data(), nv);
  gv.setZero();
  if (with_hessian) {
    Eigen::Map<Eigen::MatrixXd> hv(w.rod_hessian.data(), nv, nv);
    hv.setZero();
    rod.add_gradient_and_hessian(gv, hv, hessian_axial_forces);
  } else {
    rod.add_gradient(gv);
  }
  if (forces) gv -= (*forces)[s];
  terminal_jacobians(linkage, s, with_hessian, w);
  local_gradient(plan, nv, w);
  if (!with_hessian) return;
  // The joints' second-derivative terms weigh the rod's gradient: in the
  // mixed Hessian, with the given axial forces (the gradient itself is
  // already stored).
  if (hessian_axial_forces)
    for (int j = 0; j < rod.num_edges(); ++j) {
      const Eigen::Vector3d f = ((*hessian_axial_forces)[j] - rod.axial_force(j)) * rod.tangent(j);
      gv.segment<3>(ElasticRod::node_dof(j)) -= f;
      gv.segment<3>(ElasticRod::node_dof(j + 1)) += f;
    }
  local_hessian(plan, nv, w);
}

void LinkageAssembly::terminal_jacobians(const RodLinkage& linkage, int s, bool with_hessian,
                                         Scratch& w) const {
  const ElasticRod& rod = linkage.segment(s);
  const SegmentTopology& seg = linkage.topology().segments[s];
  const SegmentPlan& plan = plans_[s];
  for (int side = 0; side < 2; ++side) {
    if (plan.joint_local[side] < 0) continue;
    const int edge = terminal_edge_index(rod, side);
    if (with_hessian) {
      terminal_edge_derivatives(joint_geometry_[seg.joint[side]], seg.label[side], seg.sign[side],
                                rod.source_frames()[edge], w.terminal[side]);
      w.jacobian[side] = w.terminal[side].jacobian;
    } else {
      terminal_edge_jacobian(joint_geometry_[seg.joint[side]], seg.label[side], seg.sign[side],
                             rod.source_frames()[edge], w.jacobian[side]);
    }
  }
}

void LinkageAssembly::local_gradient(const SegmentPlan& plan, int nv, Scratch& w) {
  const Eigen::Map<const Eigen::VectorXd> gv(w.rod_gradient.data(), nv);
  const int nf = static_cast<int>(plan.free_full.size());
  Eigen::Map<Eigen::VectorXd> lg(w.local_gradient.data(), plan.size());
  for (int i = 0; i < nf; ++i) lg[i] = gv[plan.free_full[i]];
  for (int side = 0; side < 2; ++side) {
    const int o = plan.joint_local[side];
    if (o < 0) continue;
    Eigen::Matrix<double, 7, 1> gc;
    for (int k = 0; k < 7; ++k) gc[k] = gv[plan.controlled[side][k]];
    lg.segment<9>(o) = w.jacobian[side].transpose() * gc;
  }
}

void LinkageAssembly::local_hessian(const SegmentPlan& plan, int nv, Scratch& w) {
  const Eigen::Map<const Eigen::MatrixXd> hv(w.rod_hessian.data(), nv, nv);
  const int m = plan.size();
  const int nf = static_cast<int>(plan.free_full.size());
  Eigen::Map<Eigen::MatrixXd> L(w.local_hessian.data(), m, m);
  // The rod's Hessian is symmetric to round-off only on some processors
  // (an AVX2 build: mirrored entries one ulp apart): each pair is read from
  // one triangle, so that L is symmetric bit for bit.
  for (int c = 0; c < nf; ++c)
    for (int r = 0; r < nf; ++r) {
      const int i = plan.free_full[r], j = plan.free_full[c];
      L(r, c) = i <= j ? hv(i, j) : hv(j, i);
    }
  for (int side = 0; side < 2; ++side) {
    const int o = plan.joint_local[side];
    if (o < 0) continue;
    for (int other = 0; other < 2; ++other)
      if (plan.joint_local[other] >= 0) L.block<9, 9>(o, plan.joint_local[other]).setZero();
  }
  for (int side = 0; side < 2; ++side)
    if (plan.joint_local[side] >= 0) add_joint_hessian(plan, side, nv, w);
}

void LinkageAssembly::add_joint_hessian(const SegmentPlan& plan, int side, int nv, Scratch& w) {
  const Eigen::Map<const Eigen::VectorXd> gv(w.rod_gradient.data(), nv);
  const Eigen::Map<const Eigen::MatrixXd> hv(w.rod_hessian.data(), nv, nv);
  Eigen::Map<Eigen::MatrixXd> L(w.local_hessian.data(), plan.size(), plan.size());
  const int o = plan.joint_local[side];
  const std::array<int, 7>& cs = plan.controlled[side];
  const std::vector<int>& rows = plan.coupled_free[side];
  const int nc = static_cast<int>(rows.size());
  auto coupling = w.coupling_rows.topRows(nc);
  for (int i = 0; i < nc; ++i)
    for (int k = 0; k < 7; ++k) coupling(i, k) = hv(plan.free_full[rows[i]], cs[k]);
  for (int i = 0; i < nc; ++i) {
    const Eigen::Matrix<double, 1, 9> row = coupling.row(i).lazyProduct(w.jacobian[side]);
    L.block<1, 9>(rows[i], o) = row;
    L.block<9, 1>(o, rows[i]) = row.transpose();
  }
  for (int other = side; other < 2; ++other) {
    const int p = plan.joint_local[other];
    if (p < 0 || (other != side && !plan.ends_coupled[side])) continue;
    Eigen::Matrix<double, 7, 7> hcc;
    for (int b = 0; b < 7; ++b)
      for (int a = 0; a < 7; ++a) hcc(a, b) = hv(cs[a], plan.controlled[other][b]);
    const Eigen::Matrix<double, 7, 9> hj = hcc.lazyProduct(w.jacobian[other]);
    const Eigen::Matrix<double, 9, 9> block = w.jacobian[side].transpose().lazyProduct(hj);
    L.block<9, 9>(o, p) += block;
    if (other != side) L.block<9, 9>(p, o) += block.transpose();
  }
  for (int k = 0; k < 7; ++k)
    L.block<6, 6>(o + 3, o + 3) += gv[cs[k]] * w.terminal[side].hessians[k];
  const Eigen::Matrix<double, 9, 9> diagonal = L.block<9, 9>(o, o);
  L.block<9, 9>(o, o) = 0.5 * (diagonal + diagonal.transpose());  // symmetric bit for bit
}

void LinkageAssembly::gradient(const RodLinkage& linkage,
                               const std::vector<Eigen::VectorXd>* forces, Eigen::VectorXd& out) {
  if (num_dofs_ != linkage.num_dofs())
    throw std::logic_error("LinkageAssembly: built for another linkage");
  prepare_scratch();
  const int ns = static_cast<int>(plans_.size());
  out.resize(num_dofs_);
  const int nj = linkage.num_joints();
  joint_geometry_.resize(nj);
  // One parallel run per evaluation (waking the team and its barriers are
  // the overhead); small linkages stay serial. Joints and segments go to the
  // threads in the same ranges at every call (affine_loop.hpp).
  ThreadTeam::shared().run(segment_threads(ns), [&](int self, int members) {
    joints_then_segments(
        self, members, nj, ns,
        [&](int j) { joint_geometry_jacobian(linkage.joint(j), joint_geometry_[j]); },
        [&](int s) {
          Scratch& w = scratch_[self];
          local_derivatives(linkage, s, forces, false, w);
          store_gradient(plans_[s], w.local_gradient.data(), out.data());
        });
    sum_gradient(out, self, members);
  });
}

void LinkageAssembly::sum_gradient(Eigen::VectorXd& out, int self, int members) const {
  const MemberRange range = member_range(static_cast<long>(shared_dofs_.size()), self, members);
  for (long k = range.first; k < range.last; ++k) {
    double sum = 0.0;
    for (long i = gradient_sources_begin_[k]; i < gradient_sources_begin_[k + 1]; ++i)
      sum += gradient_contributions_[gradient_sources_[i]];
    out[shared_dofs_[k]] = sum;
  }
}

void LinkageAssembly::hessian(const RodLinkage& linkage, const std::vector<Eigen::VectorXd>* forces,
                              Eigen::SparseMatrix<double>& out, Eigen::VectorXd* gradient,
                              const std::vector<Eigen::VectorXd>* hessian_axial_forces) {
  if (num_dofs_ != linkage.num_dofs())
    throw std::logic_error("LinkageAssembly: built for another linkage");
  prepare_scratch();
  // `out` keeps pattern_ between calls; check it fully only when it is not
  // the matrix written last time.
  const bool known = &out == last_output_ && out.valuePtr() == last_values_ &&
                     out.nonZeros() == pattern_.nonZeros();
  if (!known) {
    const bool same_pattern =
        out.rows() == pattern_.rows() && out.cols() == pattern_.cols() && out.isCompressed() &&
        out.nonZeros() == pattern_.nonZeros() &&
        std::equal(pattern_.outerIndexPtr(), pattern_.outerIndexPtr() + pattern_.cols() + 1,
                   out.outerIndexPtr()) &&
        std::equal(pattern_.innerIndexPtr(), pattern_.innerIndexPtr() + pattern_.nonZeros(),
                   out.innerIndexPtr());
    if (!same_pattern) out = pattern_;
    last_output_ = &out;
    last_values_ = out.valuePtr();
  }
  double* values = out.valuePtr();
  if (gradient) gradient->resize(num_dofs_);
  const long shared = static_cast<long>(shared_slots_.size());
  const int nj = linkage.num_joints();
  joint_geometry_.resize(nj);
  const int ns = static_cast<int>(plans_.size());
  ThreadTeam::shared().run(segment_threads(ns), [&](int self, int members) {
    joints_then_segments(
        self, members, nj, ns,
        [&](int j) { joint_geometry_derivatives(linkage.joint(j), joint_geometry_[j]); },
        [&](int s) {
          Scratch& w = scratch_[self];
          local_derivatives(linkage, s, forces, true, w,
                            hessian_axial_forces ? &(*hessian_axial_forces)[s] : nullptr);
          const SegmentPlan& plan = plans_[s];
          const double* local = w.local_hessian.data();  // column-major, plan.size() square
          copy_runs(plan.shared_runs, local, hessian_contributions_.data() + plan.hessian_begin);
          copy_runs(plan.direct_runs, local, values);
          if (gradient) store_gradient(plan, w.local_gradient.data(), gradient->data());
        });
    const MemberRange range = member_range(shared, self, members);
    for (long k = range.first; k < range.last; ++k) {
      double sum = 0.0;
      for (long i = hessian_sources_begin_[k]; i < hessian_sources_begin_[k + 1]; ++i)
        sum += hessian_contributions_[hessian_sources_[i]];
      values[shared_slots_[k]] = sum;
    }
    if (gradient) sum_gradient(*gradient, self, members);
  });
}

}  // namespace xshell
