#include "linkage_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/dual1.hpp"
#include "math/rotation.hpp"
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

// Chunk of a dynamically scheduled loop over count items: at most
// `largest`, and small enough that every thread of the team gets about
// eight chunks (a small linkage's 40 segments in chunks of 8 left one of
// two threads with 3 chunks and the other with 2).
int chunk_size(int count, int largest) {
#ifdef _OPENMP
  const int threads = omp_get_num_threads();
#else
  const int threads = 1;
#endif
  return std::max(1, std::min(largest, count / (8 * threads)));
}

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

int terminal_edge_index(const ElasticRod& rod, int side) { return side == 0 ? 0 : rod.num_edges() - 1; }

}  // namespace

XSHELL_FLATTEN void terminal_edge_jacobian(const Joint& joint, int label, int sign, const SourceFrame& source,
                            double theta_hint, Eigen::Matrix<double, 7, 9>& jacobian) {
  using D = Dual1<9>;
  D q[9];
  for (int i = 0; i < 9; ++i) q[i] = D::variable(i, joint.params()[i]);
  const TerminalEdge<D> t = joint.terminal_edge<D>(q, label, sign, source, theta_hint);
  const D* out[7] = {&t.first.x, &t.first.y, &t.first.z, &t.second.x, &t.second.y, &t.second.z, &t.theta};
  for (int k = 0; k < 7; ++k) jacobian.row(k) = out[k]->g.transpose();
}

namespace {
// The joint's geometry v = (e_A, e_B, n) in forward-mode duals D seeded on
// parameters 3..8 (p enters as a constant).
template <class D>
std::array<D, 9> joint_geometry_duals(const Joint& joint) {
  D q[9];
  for (int i = 0; i < 3; ++i) q[i] = D(joint.params()[i]);
  for (int i = 3; i < 9; ++i) q[i] = D::variable(i - 3, joint.params()[i]);
  V3<D> e_a, e_b, n;
  joint.geometry<D>(q, e_a, e_b, n);
  return {e_a.x, e_a.y, e_a.z, e_b.x, e_b.y, e_b.z, n.x, n.y, n.z};
}
}  // namespace

XSHELL_FLATTEN void joint_geometry_derivatives_by_ad(const Joint& joint, JointGeometryDerivatives& out) {
  const std::array<Dual<6>, 9> v = joint_geometry_duals<Dual<6>>(joint);
  for (int k = 0; k < 9; ++k) {
    out.value[k] = v[k].v;
    out.jacobian.row(k) = v[k].g.transpose();
    out.hessians[k] = v[k].h;
  }
}

namespace {
// Rotation joints (joint.hpp): with c = cos(alpha/2), s = sin(alpha/2),
//   e_A = l_A R(w) (c b1 - s b2),  e_B = l_B R(w) (c b1 + s b2),  n = R(w) n0,
// so R(w) b1, R(w) b2, R(w) n0 by second-order AD over w alone (Dual<3>)
// give everything; the alpha and length derivatives are written out.
// Local parameter order: w (0-2), alpha (3), l_A (4), l_B (5).
XSHELL_FLATTEN void rotation_joint_geometry_derivatives(const Joint& joint, JointGeometryDerivatives& out) {
  using D = Dual<3>;
  const JointParams& q = joint.params();
  const V3<D> w(D::variable(0, q[kOmega]), D::variable(1, q[kOmega + 1]), D::variable(2, q[kOmega + 2]));
  const Eigen::Matrix3d& frame = joint.reference_frame();
  V3<D> rotated[3];
  for (int k = 0; k < 3; ++k) rotated[k] = rotate(w, lift<D>(frame.col(k)));
  const D* r1[3] = {&rotated[0].x, &rotated[0].y, &rotated[0].z};
  const D* r2[3] = {&rotated[1].x, &rotated[1].y, &rotated[1].z};
  const D* rn[3] = {&rotated[2].x, &rotated[2].y, &rotated[2].z};
  const double c = std::cos(0.5 * q[kAlpha]), s = std::sin(0.5 * q[kAlpha]);
  for (int label = 0; label < 2; ++label) {
    const double sign = label == 0 ? -1.0 : 1.0;
    const double l = q[kLengthA + label];
    const int li = 4 + label;  // local index of l_X
    // u = a r1 + b r2 and its alpha derivatives.
    const double a = c, b = sign * s, da = -0.5 * s, db = 0.5 * sign * c, dda = -0.25 * c, ddb = -0.25 * sign * s;
    for (int k = 0; k < 3; ++k) {
      const D& p = *r1[k];
      const D& m = *r2[k];
      const int row = 3 * label + k;
      const double u = a * p.v + b * m.v, du = da * p.v + db * m.v;
      const Eigen::Vector3d gu = a * p.g + b * m.g, gdu = da * p.g + db * m.g;
      out.value[row] = l * u;
      out.jacobian.row(row).setZero();
      out.jacobian.block<1, 3>(row, 0) = l * gu.transpose();
      out.jacobian(row, 3) = l * du;
      out.jacobian(row, li) = u;
      Eigen::Matrix<double, 6, 6>& h = out.hessians[row];
      h.setZero();
      const Eigen::Matrix3d hw = l * (a * p.h + b * m.h);
      h.block<3, 3>(0, 0) = 0.5 * (hw + hw.transpose());  // symmetric bit for bit
      h.block<3, 1>(0, 3) = l * gdu;
      h.block<3, 1>(0, li) = gu;
      h(3, 3) = l * (dda * p.v + ddb * m.v);
      h(3, li) = du;
      h.block<1, 3>(3, 0) = h.block<3, 1>(0, 3).transpose();
      h.block<1, 3>(li, 0) = h.block<3, 1>(0, li).transpose();
      h(li, 3) = du;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const D& n = *rn[k];
    out.value[6 + k] = n.v;
    out.jacobian.row(6 + k).setZero();
    out.jacobian.block<1, 3>(6 + k, 0) = n.g.transpose();
    out.hessians[6 + k].setZero();
    out.hessians[6 + k].block<3, 3>(0, 0) = 0.5 * (n.h + n.h.transpose());
  }
}
}  // namespace

void joint_geometry_derivatives(const Joint& joint, JointGeometryDerivatives& out) {
  if (joint.kind() == JointKind::Rotation)
    rotation_joint_geometry_derivatives(joint, out);
  else
    joint_geometry_derivatives_by_ad(joint, out);
}

XSHELL_FLATTEN void joint_geometry_jacobian(const Joint& joint, JointGeometryDerivatives& out) {
  const std::array<Dual1<6>, 9> v = joint_geometry_duals<Dual1<6>>(joint);
  for (int k = 0; k < 9; ++k) {
    out.value[k] = v[k].v;
    out.jacobian.row(k) = v[k].g.transpose();
  }
}

namespace {
// dtheta/de and dtheta/dn of a terminal edge's theta (see the header).
template <class T>
void theta_gradient(const V3<T>& e, const V3<T>& n, const SourceFrame& source, V3<T>& ge, V3<T>& gn) {
  const T l = norm(e);
  const V3<T> t = e * (1.0 / l);
  Frame<T> ref;
  V3<T> kh;
  detail::transported_frame(t, source, ref, kh);
  const T y = -dot(n, ref.d1), x = dot(n, ref.d2);
  const V3<T> u = (ref.d1 * x + ref.d2 * y) * (1.0 / (x * x + y * y));
  gn = -u;
  const V3<T> g = u * dot(n, t) + kh * 0.5;
  ge = (g - t * dot(g, t)) * (1.0 / l);
}
}  // namespace

namespace {

// Rows 0-5 of a terminal edge's Jacobian: the nodes p -/+ (s/2) e_X.
void node_jacobian(const JointGeometryDerivatives& geometry, int e0, double s,
                   Eigen::Matrix<double, 7, 9>& jacobian) {
  jacobian.setZero();
  for (int c = 0; c < 3; ++c) {
    jacobian(c, c) = 1.0;
    jacobian(3 + c, c) = 1.0;
    jacobian.block<1, 6>(c, 3) = (-0.5 * s) * geometry.jacobian.row(e0 + c);
    jacobian.block<1, 6>(3 + c, 3) = (0.5 * s) * geometry.jacobian.row(e0 + c);
  }
}

// d u / d params[3..8] for u = (s e_X, n).
Eigen::Matrix<double, 6, 6> edge_and_normal_jacobian(const JointGeometryDerivatives& geometry, int e0, double s) {
  Eigen::Matrix<double, 6, 6> ju;
  for (int c = 0; c < 3; ++c) {
    ju.row(c) = s * geometry.jacobian.row(e0 + c);
    ju.row(3 + c) = geometry.jacobian.row(6 + c);
  }
  return ju;
}

}  // namespace

XSHELL_FLATTEN void terminal_edge_jacobian(const JointGeometryDerivatives& geometry, int label, int sign,
                            const SourceFrame& source, Eigen::Matrix<double, 7, 9>& jacobian) {
  const double s = static_cast<double>(sign);
  const int e0 = 3 * label;
  node_jacobian(geometry, e0, s, jacobian);
  const V3<double> e(s * geometry.value[e0], s * geometry.value[e0 + 1], s * geometry.value[e0 + 2]);
  const V3<double> n(geometry.value[6], geometry.value[7], geometry.value[8]);
  V3<double> ge, gn;
  theta_gradient(e, n, source, ge, gn);
  const Eigen::Matrix<double, 6, 1> g(ge.x, ge.y, ge.z, gn.x, gn.y, gn.z);
  jacobian.block<1, 6>(6, 3) = g.transpose() * edge_and_normal_jacobian(geometry, e0, s);
}

XSHELL_FLATTEN void terminal_edge_derivatives(const JointGeometryDerivatives& geometry, int label, int sign,
                               const SourceFrame& source, TerminalEdgeDerivatives& out) {
  const double s = static_cast<double>(sign);
  const int e0 = 3 * label;  // rows of e_X in the geometry
  node_jacobian(geometry, e0, s, out.jacobian);
  for (int c = 0; c < 3; ++c) {
    out.hessians[c] = (-0.5 * s) * geometry.hessians[e0 + c];
    out.hessians[3 + c] = (0.5 * s) * geometry.hessians[e0 + c];
  }
  // theta(u), u = (s e_X, n): gradient in closed form, Hessian as its
  // Jacobian, both chained through the geometry.
  using D = Dual1<6>;
  const V3<D> e(D::variable(0, s * geometry.value[e0]), D::variable(1, s * geometry.value[e0 + 1]),
                D::variable(2, s * geometry.value[e0 + 2]));
  const V3<D> n(D::variable(3, geometry.value[6]), D::variable(4, geometry.value[7]), D::variable(5, geometry.value[8]));
  V3<D> ge, gn;
  theta_gradient(e, n, source, ge, gn);
  const D* gu[6] = {&ge.x, &ge.y, &ge.z, &gn.x, &gn.y, &gn.z};
  Eigen::Matrix<double, 6, 1> g;
  Eigen::Matrix<double, 6, 6> h;
  for (int k = 0; k < 6; ++k) {
    g[k] = gu[k]->v;
    h.row(k) = gu[k]->g.transpose();
  }
  const Eigen::Matrix<double, 6, 6> hu = 0.5 * (h + h.transpose());
  const Eigen::Matrix<double, 6, 6> ju = edge_and_normal_jacobian(geometry, e0, s);
  out.jacobian.block<1, 6>(6, 3) = g.transpose() * ju;
  Eigen::Matrix<double, 6, 6> ht = ju.transpose() * hu * ju;
  for (int c = 0; c < 3; ++c) {
    ht += (g[c] * s) * geometry.hessians[e0 + c];
    ht += g[3 + c] * geometry.hessians[6 + c];
  }
  out.hessians[6] = 0.5 * (ht + ht.transpose());
}

LinkageAssembly::LinkageAssembly(const RodLinkage& linkage, const std::vector<int>& free_position)
    : num_dofs_(linkage.num_dofs()), free_position_(free_position) {
  if (static_cast<int>(free_position.size()) != linkage.num_dofs())
    throw std::invalid_argument("LinkageAssembly: one free position per reduced unknown");
  const int ns = linkage.num_segments();
  plans_.resize(ns);
  std::vector<Eigen::Triplet<double>> pattern_entries;
  std::vector<std::array<int, 2>> contribution_entry;  // (free row, free column) per Hessian contribution
  std::vector<std::vector<int>> kept_entries(ns);       // per segment, its local entries (column-major index)
  long gradient_count = 0;
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
        throw std::logic_error("LinkageAssembly: joint-controlled variables differ from the linkage's");
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
      for (int k = 0; k < 9; ++k) plan.global.push_back(linkage.joint_dof_offset(seg.joint[side]) + k);
    }
    max_rod_dofs_ = std::max(max_rod_dofs_, rod.num_dofs());
    max_local_ = std::max(max_local_, plan.size());
    plan.gradient_begin = gradient_count;
    gradient_count += plan.size();

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
      for (int r = 0; r < free_count; ++r) local(r, c) = rod_pattern(plan.free_full[r], plan.free_full[c]);
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
  for (size_t i = 0; i < shared_slots_.size(); ++i) hessian_sources_begin_[i + 1] += hessian_sources_begin_[i];
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

  gradient_sources_begin_.assign(num_dofs_ + 1, 0);
  for (const SegmentPlan& plan : plans_)
    for (int r : plan.global) ++gradient_sources_begin_[r + 1];
  for (int k = 0; k < num_dofs_; ++k) gradient_sources_begin_[k + 1] += gradient_sources_begin_[k];
  gradient_sources_.resize(gradient_count);
  fill.assign(gradient_sources_begin_.begin(), gradient_sources_begin_.end() - 1);
  for (const SegmentPlan& plan : plans_)
    for (int i = 0; i < plan.size(); ++i) gradient_sources_[fill[plan.global[i]]++] = plan.gradient_begin + i;
  gradient_contributions_.assign(gradient_count, 0.0);
}

bool LinkageAssembly::matches(const RodLinkage& linkage, const std::vector<int>& free_position) const {
  return num_dofs_ == linkage.num_dofs() && static_cast<int>(plans_.size()) == linkage.num_segments() &&
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
                                        const std::vector<Eigen::VectorXd>* forces, bool with_hessian,
                                        Scratch& w) const {
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
    for (int k = 0; k < 7; ++k) L.block<6, 6>(o + 3, o + 3) += gv[cs[k]] * w.terminal[side].hessians[k];
    const Eigen::Matrix<double, 9, 9> diagonal = L.block<9, 9>(o, o);
    L.block<9, 9>(o, o) = 0.5 * (diagonal + diagonal.transpose());  // symmetric bit for bit
  }
}

void LinkageAssembly::gradient(const RodLinkage& linkage, const std::vector<Eigen::VectorXd>* forces,
                               Eigen::VectorXd& out) {
  if (num_dofs_ != linkage.num_dofs()) throw std::logic_error("LinkageAssembly: built for another linkage");
  prepare_scratch();
  const int ns = static_cast<int>(plans_.size());
  out.resize(num_dofs_);
  const int nj = linkage.num_joints();
  joint_geometry_.resize(nj);
  // One parallel region per evaluation (its fork and barriers are the
  // overhead); small linkages stay serial.
#pragma omp parallel if (ns >= kMinParallelSegments)
  {
    const int joint_chunk = chunk_size(nj, 16), segment_chunk = chunk_size(ns, 8);
#pragma omp for schedule(dynamic, joint_chunk)
    for (int j = 0; j < nj; ++j) joint_geometry_jacobian(linkage.joint(j), joint_geometry_[j]);
#pragma omp for schedule(dynamic, segment_chunk)
    for (int s = 0; s < ns; ++s) {
      Scratch& w = scratch_for_thread();
      local_derivatives(linkage, s, forces, false, w);
      std::copy(w.local_gradient.begin(), w.local_gradient.begin() + plans_[s].size(),
                gradient_contributions_.begin() + plans_[s].gradient_begin);
    }
    sum_gradient(out);
  }
}

void LinkageAssembly::sum_gradient(Eigen::VectorXd& out) const {
#pragma omp for schedule(static)
  for (int k = 0; k < num_dofs_; ++k) {
    double sum = 0.0;
    for (long i = gradient_sources_begin_[k]; i < gradient_sources_begin_[k + 1]; ++i)
      sum += gradient_contributions_[gradient_sources_[i]];
    out[k] = sum;
  }
}

void LinkageAssembly::hessian(const RodLinkage& linkage, const std::vector<Eigen::VectorXd>* forces,
                              Eigen::SparseMatrix<double>& out, Eigen::VectorXd* gradient) {
  if (num_dofs_ != linkage.num_dofs()) throw std::logic_error("LinkageAssembly: built for another linkage");
  prepare_scratch();
  // `out` keeps pattern_ between calls; check it fully only when it is not
  // the matrix written last time.
  const bool known = &out == last_output_ && out.valuePtr() == last_values_ && out.nonZeros() == pattern_.nonZeros();
  if (!known) {
    const bool same_pattern =
        out.rows() == pattern_.rows() && out.cols() == pattern_.cols() && out.isCompressed() &&
        out.nonZeros() == pattern_.nonZeros() &&
        std::equal(pattern_.outerIndexPtr(), pattern_.outerIndexPtr() + pattern_.cols() + 1, out.outerIndexPtr()) &&
        std::equal(pattern_.innerIndexPtr(), pattern_.innerIndexPtr() + pattern_.nonZeros(), out.innerIndexPtr());
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
    const int joint_chunk = chunk_size(nj, 16), segment_chunk = chunk_size(ns, 8);
#pragma omp for schedule(dynamic, joint_chunk)
    for (int j = 0; j < nj; ++j) joint_geometry_derivatives(linkage.joint(j), joint_geometry_[j]);
#pragma omp for schedule(dynamic, segment_chunk)
    for (int s = 0; s < ns; ++s) {
      Scratch& w = scratch_for_thread();
      local_derivatives(linkage, s, forces, true, w);
      const SegmentPlan& plan = plans_[s];
      const double* local = w.local_hessian.data();  // column-major, plan.size() square
      double* target = hessian_contributions_.data() + plan.hessian_begin;
      for (const CopyRun& run : plan.shared_runs)
        for (int i = 0; i < run.length; ++i) target[run.target + i] = local[run.first + i];
      for (const CopyRun& run : plan.direct_runs)
        for (int i = 0; i < run.length; ++i) values[run.target + i] = local[run.first + i];
      if (gradient)
        std::copy(w.local_gradient.begin(), w.local_gradient.begin() + plan.size(),
                  gradient_contributions_.begin() + plan.gradient_begin);
    }
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
