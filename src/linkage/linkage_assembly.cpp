#include "linkage_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "segment_parallel.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace xshell {

namespace {

int thread_count() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Joints are taken by pairs: one costs about a microsecond, a segment
// several.
constexpr int kJointChunk = 2;

int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// Full variables a joint controls at one end of a segment, in the order of
// TerminalEdge (first node, second node, theta); rod_linkage.cpp sets the
// same ones.
std::array<int, 7> terminal_variables(const ElasticRod& rod, int side) {
  const int node = side == 0 ? 0 : rod.num_edges() - 1;
  std::array<int, 7> v;
  for (int c = 0; c < 3; ++c) {
    v[c] = ElasticRod::node_dof(node) + c;
    v[3 + c] = ElasticRod::node_dof(node + 1) + c;
  }
  v[6] = rod.theta_dof(node);
  return v;
}

int terminal_edge_index(const ElasticRod& rod, int side) {
  return side == 0 ? 0 : rod.num_edges() - 1;
}

}  // namespace

LinkageAssembly::LinkageAssembly(const RodLinkage& linkage, const std::vector<int>& free_position)
    : num_dofs_(linkage.num_dofs()), free_position_(free_position) {
  if (static_cast<int>(free_position.size()) != linkage.num_dofs())
    throw std::invalid_argument("LinkageAssembly: one free position per reduced unknown");
  const int ns = linkage.num_segments();
  plans_.resize(ns);
  std::vector<Eigen::Triplet<double>> pattern_entries;
  std::vector<std::array<int, 2>>
      contribution_entry;  // (free row, free column) per Hessian contribution
  std::vector<std::vector<int>> kept_entries(
      ns);  // per segment, its local entries (column-major index)
  for (int s = 0; s < ns; ++s) {
    const ElasticRod& rod = linkage.segment(s);
    const SegmentTopology& seg = linkage.topology().segments[s];
    SegmentPlan& plan = plans_[s];
    // Local unknowns: free full variables in reduced order, then joint blocks.
    const int offset = linkage.segment_dof_offset(s);
    std::vector<int> controlled_mask(rod.num_dofs(), 0);
    for (int side = 0; side < 2; ++side) {
      if (seg.joint[side] < 0) continue;
      plan.controlled[side] = terminal_variables(rod, side);
      for (int v : plan.controlled[side]) controlled_mask[v] = 1;
    }
    for (int k = 0; k < rod.num_dofs(); ++k) {
      const int r = linkage.reduced_index(s, k);
      if ((r < 0) != (controlled_mask[k] == 1))
        throw std::logic_error(
            "LinkageAssembly: joint-controlled variables differ from the linkage's");
    }
    int free_count = 0;
    for (int k = 0; k < rod.num_dofs(); ++k)
      if (linkage.reduced_index(s, k) >= 0) ++free_count;
    plan.free_full.assign(free_count, -1);
    for (int k = 0; k < rod.num_dofs(); ++k) {
      const int r = linkage.reduced_index(s, k);
      if (r >= 0) plan.free_full[r - offset] = k;
    }
    for (int i = 0; i < free_count; ++i) plan.global.push_back(offset + i);
    for (int side = 0; side < 2; ++side) {
      if (seg.joint[side] < 0) continue;
      plan.joint_local[side] = static_cast<int>(plan.global.size());
      for (int k = 0; k < 9; ++k)
        plan.global.push_back(linkage.joint_dof_offset(seg.joint[side]) + k);
    }
    max_rod_dofs_ = std::max(max_rod_dofs_, rod.num_dofs());
    max_local_ = std::max(max_local_, plan.size());

    // Structure of the local Hessian from the rod's: free-free as is; a
    // free row touching any controlled variable of a joint couples to all 9
    // of its parameters; joint blocks are full (their own second
    // derivatives) and couple to each other when the rod couples their
    // terminal values.
    const Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> rod_pattern = rod.hessian_pattern();
    const int m = plan.size();
    Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> local =
        Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>::Constant(m, m, false);
    for (int c = 0; c < free_count; ++c)
      for (int r = 0; r < free_count; ++r)
        local(r, c) = rod_pattern(plan.free_full[r], plan.free_full[c]);
    for (int side = 0; side < 2; ++side) {
      const int o = plan.joint_local[side];
      if (o < 0) continue;
      local.block(o, o, 9, 9).setConstant(true);
      for (int r = 0; r < free_count; ++r) {
        bool coupled = false;
        for (int v : plan.controlled[side]) coupled = coupled || rod_pattern(plan.free_full[r], v);
        if (!coupled) continue;
        plan.coupled_free[side].push_back(r);
        local.block(r, o, 1, 9).setConstant(true);
        local.block(o, r, 9, 1).setConstant(true);
      }
      const int other = plan.joint_local[1 - side];
      if (other < 0) continue;
      bool coupled = false;
      for (int a : plan.controlled[side])
        for (int b : plan.controlled[1 - side]) coupled = coupled || rod_pattern(a, b);
      plan.ends_coupled[side] = coupled;
      if (coupled) local.block(o, other, 9, 9).setConstant(true);
    }
    plan.hessian_begin = static_cast<long>(contribution_entry.size());
    for (int c = 0; c < m; ++c) {
      const int fc = free_position[plan.global[c]];
      if (fc < 0) continue;
      for (int r = 0; r < m; ++r) {
        const int fr = free_position[plan.global[r]];
        if (fr < 0 || !local(r, c)) continue;
        kept_entries[s].push_back(r + m * c);
        contribution_entry.push_back({fr, fc});
        pattern_entries.emplace_back(fr, fc, 0.0);
      }
    }
  }

  int num_free = 0;
  for (int p : free_position) num_free = std::max(num_free, p + 1);
  pattern_.resize(num_free, num_free);
  pattern_.setFromTriplets(pattern_entries.begin(), pattern_entries.end());
  pattern_.makeCompressed();

  // Gather lists, in contribution order (segment order) for every entry.
  auto slot_of = [&](int row, int col) {
    const int* begin = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col];
    const int* end = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col + 1];
    return static_cast<long>(std::lower_bound(begin, end, row) - pattern_.innerIndexPtr());
  };
  const long nnz = pattern_.nonZeros();
  std::vector<long> slot(contribution_entry.size());
  std::vector<int> sources_of_slot(nnz, 0);
  for (size_t k = 0; k < contribution_entry.size(); ++k) {
    slot[k] = slot_of(contribution_entry[k][0], contribution_entry[k][1]);
    ++sources_of_slot[slot[k]];
  }
  // An entry with one contribution is written directly by its segment; the
  // others are summed from the contribution buffer in segment order.
  std::vector<long> shared_index(nnz, -1);
  for (long k = 0; k < nnz; ++k)
    if (sources_of_slot[k] > 1) {
      shared_index[k] = static_cast<long>(shared_slots_.size());
      shared_slots_.push_back(k);
    }
  hessian_sources_begin_.assign(shared_slots_.size() + 1, 0);
  for (long k : shared_slots_) hessian_sources_begin_[shared_index[k] + 1] = sources_of_slot[k];
  for (size_t i = 0; i < shared_slots_.size(); ++i)
    hessian_sources_begin_[i + 1] += hessian_sources_begin_[i];
  hessian_sources_.resize(hessian_sources_begin_.back());
  std::vector<long> fill(hessian_sources_begin_.begin(), hessian_sources_begin_.end() - 1);
  // Appends local entry -> target to runs, extending the last run when both
  // follow on from it.
  const auto append = [](std::vector<CopyRun>& runs, int entry, long target) {
    if (!runs.empty()) {
      CopyRun& last = runs.back();
      if (last.first + last.length == entry && last.target + last.length == target) {
        ++last.length;
        return;
      }
    }
    runs.push_back({entry, 1, target});
  };
  long shared_count = 0;
  for (int s = 0; s < ns; ++s) {
    SegmentPlan& plan = plans_[s];
    const std::vector<int>& entries = kept_entries[s];
    const long first = plan.hessian_begin;
    plan.hessian_begin = shared_count;
    for (size_t i = 0; i < entries.size(); ++i) {
      const long k = slot[first + static_cast<long>(i)];
      if (shared_index[k] < 0) {
        append(plan.direct_runs, entries[i], k);
      } else {
        append(plan.shared_runs, entries[i], shared_count - plan.hessian_begin);
        hessian_sources_[fill[shared_index[k]]++] = shared_count++;
      }
    }
  }
  hessian_contributions_.assign(shared_count, 0.0);

  // The gradient likewise: an unknown of one segment alone (its interior
  // nodes and thetas) is written by that segment; a joint's, summed.
  std::vector<int> sources_of_dof(num_dofs_, 0);
  for (const SegmentPlan& plan : plans_)
    for (int r : plan.global) ++sources_of_dof[r];
  std::vector<long> shared_dof_index(num_dofs_, -1);
  for (int k = 0; k < num_dofs_; ++k)
    if (sources_of_dof[k] != 1) {
      shared_dof_index[k] = static_cast<long>(shared_dofs_.size());
      shared_dofs_.push_back(k);
    }
  gradient_sources_begin_.assign(shared_dofs_.size() + 1, 0);
  for (size_t i = 0; i < shared_dofs_.size(); ++i)
    gradient_sources_begin_[i + 1] = gradient_sources_begin_[i] + sources_of_dof[shared_dofs_[i]];
  gradient_sources_.resize(gradient_sources_begin_.back());
  fill.assign(gradient_sources_begin_.begin(), gradient_sources_begin_.end() - 1);
  long gradient_shared_count = 0;
  for (SegmentPlan& plan : plans_) {
    plan.gradient_begin = gradient_shared_count;
    for (int i = 0; i < plan.size(); ++i) {
      const int r = plan.global[i];
      if (shared_dof_index[r] < 0) {
        append(plan.gradient_direct_runs, i, r);
      } else {
        append(plan.gradient_shared_runs, i, gradient_shared_count - plan.gradient_begin);
        gradient_sources_[fill[shared_dof_index[r]]++] = gradient_shared_count++;
      }
    }
  }
  gradient_contributions_.assign(gradient_shared_count, 0.0);
}

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
void LinkageAssembly::joints_then_segments(int num_joints, int num_segments, JointWork&& joint_work,
                                           SegmentWork&& segment_work) {
#pragma omp single
  {
    joint_loop_.reset(num_joints);
    segment_loop_.reset(num_segments);
  }
  joint_loop_.run(kJointChunk, joint_work);
#pragma omp barrier
  segment_loop_.run(1, segment_work);
#pragma omp barrier
}

bool LinkageAssembly::matches(const RodLinkage& linkage,
                              const std::vector<int>& free_position) const {
  return num_dofs_ == linkage.num_dofs() &&
         static_cast<int>(plans_.size()) == linkage.num_segments() &&
         free_position_ == free_position;
}

LinkageAssembly::Scratch& LinkageAssembly::scratch_for_thread() { return scratch_[thread_index()]; }

void LinkageAssembly::prepare_scratch() {
  if (static_cast<int>(scratch_.size()) >= thread_count()) return;
  scratch_.resize(thread_count());
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
                                        bool with_hessian, Scratch& w) const {
  const ElasticRod& rod = linkage.segment(s);
  const SegmentTopology& seg = linkage.topology().segments[s];
  const SegmentPlan& plan = plans_[s];
  const int nv = rod.num_dofs(), m = plan.size();
  const int nf = static_cast<int>(plan.free_full.size());
  Eigen::Map<Eigen::VectorXd> gv(w.rod_gradient.data(), nv);
  gv.setZero();
  if (with_hessian) {
    Eigen::Map<Eigen::MatrixXd> hv(w.rod_hessian.data(), nv, nv);
    hv.setZero();
    rod.add_gradient_and_hessian(gv, hv);
  } else {
    rod.add_gradient(gv);
  }
  if (forces) gv -= (*forces)[s];

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

  // Gradient: free variables map to themselves, joint blocks get J^T g.
  Eigen::Map<Eigen::VectorXd> lg(w.local_gradient.data(), m);
  for (int i = 0; i < nf; ++i) lg[i] = gv[plan.free_full[i]];
  for (int side = 0; side < 2; ++side) {
    const int o = plan.joint_local[side];
    if (o < 0) continue;
    Eigen::Matrix<double, 7, 1> gc;
    for (int k = 0; k < 7; ++k) gc[k] = gv[plan.controlled[side][k]];
    lg.segment<9>(o) = w.jacobian[side].transpose() * gc;
  }
  if (!with_hessian) return;

  // Hessian: J^T H J by blocks, plus the joints' second derivatives. Only
  // entries in the plan's pattern are read afterwards: all free-free ones,
  // the rows of free unknowns coupled to an end, and the joint blocks (the
  // only ones accumulated, so the only ones zeroed).
  const Eigen::Map<const Eigen::MatrixXd> hv(w.rod_hessian.data(), nv, nv);
  Eigen::Map<Eigen::MatrixXd> L(w.local_hessian.data(), m, m);
  for (int c = 0; c < nf; ++c)
    for (int r = 0; r < nf; ++r) L(r, c) = hv(plan.free_full[r], plan.free_full[c]);
  for (int side = 0; side < 2; ++side) {
    const int o = plan.joint_local[side];
    if (o < 0) continue;
    for (int other = 0; other < 2; ++other)
      if (plan.joint_local[other] >= 0) L.block<9, 9>(o, plan.joint_local[other]).setZero();
  }
  for (int side = 0; side < 2; ++side) {
    const int o = plan.joint_local[side];
    if (o < 0) continue;
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
  // One parallel region per evaluation (its fork and barriers are the
  // overhead); small linkages stay serial. Joints and segments go to the
  // threads in the same ranges at every call (affine_loop.hpp).
#pragma omp parallel if (ns >= kMinParallelSegments)
  {
    joints_then_segments(
        nj, ns, [&](int j) { joint_geometry_jacobian(linkage.joint(j), joint_geometry_[j]); },
        [&](int s) {
          Scratch& w = scratch_for_thread();
          local_derivatives(linkage, s, forces, false, w);
          store_gradient(plans_[s], w.local_gradient.data(), out.data());
        });
    sum_gradient(out);
  }
}

void LinkageAssembly::sum_gradient(Eigen::VectorXd& out) const {
  const long shared = static_cast<long>(shared_dofs_.size());
#pragma omp for schedule(static)
  for (long k = 0; k < shared; ++k) {
    double sum = 0.0;
    for (long i = gradient_sources_begin_[k]; i < gradient_sources_begin_[k + 1]; ++i)
      sum += gradient_contributions_[gradient_sources_[i]];
    out[shared_dofs_[k]] = sum;
  }
}

void LinkageAssembly::hessian(const RodLinkage& linkage, const std::vector<Eigen::VectorXd>* forces,
                              Eigen::SparseMatrix<double>& out, Eigen::VectorXd* gradient) {
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
#pragma omp parallel if (ns >= kMinParallelSegments)
  {
    joints_then_segments(
        nj, ns, [&](int j) { joint_geometry_derivatives(linkage.joint(j), joint_geometry_[j]); },
        [&](int s) {
          Scratch& w = scratch_for_thread();
          local_derivatives(linkage, s, forces, true, w);
          const SegmentPlan& plan = plans_[s];
          const double* local = w.local_hessian.data();  // column-major, plan.size() square
          copy_runs(plan.shared_runs, local, hessian_contributions_.data() + plan.hessian_begin);
          copy_runs(plan.direct_runs, local, values);
          if (gradient) store_gradient(plan, w.local_gradient.data(), gradient->data());
        });
#pragma omp for schedule(static)
    for (long k = 0; k < shared; ++k) {
      double sum = 0.0;
      for (long i = hessian_sources_begin_[k]; i < hessian_sources_begin_[k + 1]; ++i)
        sum += hessian_contributions_[hessian_sources_[i]];
      values[shared_slots_[k]] = sum;
    }
    if (gradient) sum_gradient(*gradient);
  }
}

}  // namespace xshell
