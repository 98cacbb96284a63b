// Construction of a LinkageAssembly (linkage_assembly.hpp): every segment's
// local unknowns and local Hessian pattern, the free Hessian's pattern, and
// where every local entry goes (its own value slot, or the contribution
// buffers summed in segment order). Set-up only: nothing here runs per
// evaluation.
#include <algorithm>
#include <stdexcept>

#include "linkage_assembly.hpp"

namespace xshell {

namespace {

// Full variables a joint controls at one end of a segment, in the order of
// TerminalEdge (first node, second node, theta); rod_linkage.cpp sets the
// same ones.
std::array<int, 7> terminal_variables(const ElasticRod& rod, int side) {
  const int node = terminal_edge_index(rod, side);
  std::array<int, 7> v;
  for (int c = 0; c < 3; ++c) {
    v[c] = ElasticRod::node_dof(node) + c;
    v[3 + c] = ElasticRod::node_dof(node + 1) + c;
  }
  v[6] = rod.theta_dof(node);
  return v;
}

}  // namespace

LinkageAssembly::LinkageAssembly(const RodLinkage& linkage, const std::vector<int>& free_position)
    : num_dofs_(linkage.num_dofs()), free_position_(free_position) {
  if (static_cast<int>(free_position.size()) != linkage.num_dofs())
    throw std::invalid_argument("LinkageAssembly: one free position per reduced unknown");
  const int ns = linkage.num_segments();
  plans_.resize(ns);
  // (free row, free column) of every Hessian contribution, and per segment
  // its kept local entries (column-major index), in the same order.
  std::vector<std::array<int, 2>> contribution_entry;
  std::vector<std::vector<int>> kept_entries(ns);
  for (int s = 0; s < ns; ++s) {
    const ElasticRod& rod = linkage.segment(s);
    SegmentPlan& plan = plans_[s];
    plan_unknowns(linkage, s, plan);
    max_rod_dofs_ = std::max(max_rod_dofs_, rod.num_dofs());
    max_local_ = std::max(max_local_, plan.size());
    const BoolMatrix local = local_pattern(rod.hessian_pattern(), plan);
    // The entries of free rows and columns, in column-major order.
    const int m = plan.size();
    plan.hessian_begin = static_cast<long>(contribution_entry.size());
    for (int c = 0; c < m; ++c) {
      const int fc = free_position[plan.global[c]];
      if (fc < 0) continue;
      for (int r = 0; r < m; ++r) {
        const int fr = free_position[plan.global[r]];
        if (fr < 0 || !local(r, c)) continue;
        kept_entries[s].push_back(r + m * c);
        contribution_entry.push_back({fr, fc});
      }
    }
  }
  build_pattern(contribution_entry);
  plan_hessian_sums(contribution_slots(contribution_entry), kept_entries);
  plan_gradient_sums();
}

void LinkageAssembly::plan_unknowns(const RodLinkage& linkage, int s, SegmentPlan& plan) {
  const ElasticRod& rod = linkage.segment(s);
  const SegmentTopology& seg = linkage.topology().segments[s];
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
}

LinkageAssembly::BoolMatrix LinkageAssembly::local_pattern(const BoolMatrix& rod_pattern,
                                                           SegmentPlan& plan) {
  const int m = plan.size();
  const int free_count = static_cast<int>(plan.free_full.size());
  BoolMatrix local = BoolMatrix::Constant(m, m, false);
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
  return local;
}

void LinkageAssembly::build_pattern(const std::vector<std::array<int, 2>>& contribution_entry) {
  std::vector<Eigen::Triplet<double>> pattern_entries;
  pattern_entries.reserve(contribution_entry.size());
  for (const std::array<int, 2>& entry : contribution_entry)
    pattern_entries.emplace_back(entry[0], entry[1], 0.0);
  int num_free = 0;
  for (int p : free_position_) num_free = std::max(num_free, p + 1);
  pattern_.resize(num_free, num_free);
  pattern_.setFromTriplets(pattern_entries.begin(), pattern_entries.end());
  pattern_.makeCompressed();
}

std::vector<long> LinkageAssembly::contribution_slots(
    const std::vector<std::array<int, 2>>& contribution_entry) const {
  std::vector<long> slot(contribution_entry.size());
  for (size_t k = 0; k < contribution_entry.size(); ++k) {
    const int row = contribution_entry[k][0], col = contribution_entry[k][1];
    const int* begin = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col];
    const int* end = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col + 1];
    slot[k] = static_cast<long>(std::lower_bound(begin, end, row) - pattern_.innerIndexPtr());
  }
  return slot;
}

void LinkageAssembly::append_run(std::vector<CopyRun>& runs, int entry, long target) {
  if (!runs.empty()) {
    CopyRun& last = runs.back();
    if (last.first + last.length == entry && last.target + last.length == target) {
      ++last.length;
      return;
    }
  }
  runs.push_back({entry, 1, target});
}

void LinkageAssembly::plan_hessian_sums(const std::vector<long>& slot,
                                        const std::vector<std::vector<int>>& kept_entries) {
  const long nnz = pattern_.nonZeros();
  std::vector<int> sources_of_slot(nnz, 0);
  for (long k : slot) ++sources_of_slot[k];
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
  long shared_count = 0;
  for (size_t s = 0; s < plans_.size(); ++s) {
    SegmentPlan& plan = plans_[s];
    const std::vector<int>& entries = kept_entries[s];
    const long first = plan.hessian_begin;
    plan.hessian_begin = shared_count;
    for (size_t i = 0; i < entries.size(); ++i) {
      const long k = slot[first + static_cast<long>(i)];
      if (shared_index[k] < 0) {
        append_run(plan.direct_runs, entries[i], k);
      } else {
        append_run(plan.shared_runs, entries[i], shared_count - plan.hessian_begin);
        hessian_sources_[fill[shared_index[k]]++] = shared_count++;
      }
    }
  }
  hessian_contributions_.assign(shared_count, 0.0);
}

void LinkageAssembly::plan_gradient_sums() {
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
  std::vector<long> fill(gradient_sources_begin_.begin(), gradient_sources_begin_.end() - 1);
  long gradient_shared_count = 0;
  for (SegmentPlan& plan : plans_) {
    plan.gradient_begin = gradient_shared_count;
    for (int i = 0; i < plan.size(); ++i) {
      const int r = plan.global[i];
      if (shared_dof_index[r] < 0) {
        append_run(plan.gradient_direct_runs, i, r);
      } else {
        append_run(plan.gradient_shared_runs, i, gradient_shared_count - plan.gradient_begin);
        gradient_sources_[fill[shared_dof_index[r]]++] = gradient_shared_count++;
      }
    }
  }
  gradient_contributions_.assign(gradient_shared_count, 0.0);
}

bool LinkageAssembly::matches(const RodLinkage& linkage,
                              const std::vector<int>& free_position) const {
  return num_dofs_ == linkage.num_dofs() &&
         static_cast<int>(plans_.size()) == linkage.num_segments() &&
         free_position_ == free_position;
}

}  // namespace xshell
