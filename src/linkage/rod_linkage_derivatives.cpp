// Gradient and Hessian of the linkage energy with respect to the reduced
// unknowns, by the chain rule through the joints (docs/model.md section 7.1):
//   dE/dr = J^T dE/dv,
//   d2E/dr2 = J^T (d2E/dv2) J + sum_k (dE/dv_k) d2v_k/dr2,
// where v are a segment's full variables (rod nodes and thetas) and J = dv/dr.
// Free variables map to themselves; a joint's terminal edge nodes and theta
// are nonlinear functions of its 9 parameters (joint.hpp), whose exact first
// and second derivatives give the rows of J and the second term. Each
// segment is handled as a small dense problem over its local unknowns (its
// free ones and the parameters of the joints at its ends) and scattered into
// the global sparse matrix; the set of entries never changes. These are the
// plain, one-off forms; the statics problem assembles through
// LinkageAssembly (linkage_assembly.hpp), which computes the same sums with
// a precomputed pattern, in parallel.
#include <array>

#include "linkage_assembly.hpp"
#include "math/dual1.hpp"
#include "rod_linkage.hpp"

namespace xshell {

RodLinkage::LocalMap RodLinkage::local_map(int s, bool with_hessians) const {
  const SegmentTopology& seg = topology_.segments[s];
  const ElasticRod& rod = rods_[s];
  const std::vector<int>& slot = slots_[s];
  LocalMap map;
  int free_count = 0;
  for (int v : slot)
    if (v >= 0) ++free_count;
  for (int k = 0; k < free_count; ++k) map.global.push_back(segment_offset_[s] + k);
  for (int side = 0; side < 2; ++side) {
    if (seg.joint[side] < 0) continue;
    map.joint_blocks.emplace_back(static_cast<int>(map.global.size()), side);
    for (int k = 0; k < 9; ++k) map.global.push_back(joint_offset_[seg.joint[side]] + k);
  }
  map.jacobian =
      Eigen::MatrixXd::Zero(rod.num_dofs(), static_cast<Eigen::Index>(map.global.size()));
  for (int k = 0; k < rod.num_dofs(); ++k)
    if (slot[k] >= 0) map.jacobian(k, slot[k] - segment_offset_[s]) = 1.0;
  for (const auto& [offset, side] : map.joint_blocks) {
    const int edge = terminal_edge_index(rod, side);
    Eigen::Matrix<double, 7, 9> jac;
    JointHessian scratch[7];
    if (with_hessians)
      joints_[seg.joint[side]].terminal_edge_derivatives(seg.label[side], seg.sign[side],
                                                         rod.source_frames()[edge],
                                                         rod.thetas()[edge], jac, scratch);
    else
      terminal_edge_jacobian(joints_[seg.joint[side]], seg.label[side], seg.sign[side],
                             rod.source_frames()[edge], rod.thetas()[edge], jac);
    for (int k = 0; k < rod.num_dofs(); ++k) {
      if (slot[k] >= 0) continue;
      const int code = -1 - slot[k];
      if (code / 7 != side) continue;
      map.jacobian.block<1, 9>(k, offset) = jac.row(code % 7);
      map.controlled[side][code % 7] = k;
    }
    if (with_hessians)
      for (int o = 0; o < 7; ++o) map.hessians[side][o] = scratch[o];
  }
  return map;
}

Eigen::VectorXd RodLinkage::gradient(const std::vector<Eigen::VectorXd>* forces) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(num_dofs_);
  for (int s = 0; s < num_segments(); ++s) {
    Eigen::VectorXd gv = rods_[s].gradient();
    if (forces) gv -= (*forces)[s];
    const LocalMap map = local_map(s, false);
    const Eigen::VectorXd local = map.jacobian.transpose() * gv;
    for (size_t k = 0; k < map.global.size(); ++k) g[map.global[k]] += local[k];
  }
  return g;
}

void RodLinkage::hessian_triplets(std::vector<Eigen::Triplet<double>>& triplets,
                                  const std::vector<Eigen::VectorXd>* forces) const {
  for (int s = 0; s < num_segments(); ++s) {
    const ElasticRod& rod = rods_[s];
    Eigen::VectorXd gv = rod.gradient();
    if (forces) gv -= (*forces)[s];
    Eigen::MatrixXd hv = Eigen::MatrixXd::Zero(rod.num_dofs(), rod.num_dofs());
    rod.add_hessian(hv);
    const LocalMap map = local_map(s, true);
    Eigen::MatrixXd local = map.jacobian.transpose() * hv * map.jacobian;
    for (const auto& [offset, side] : map.joint_blocks)
      for (int o = 0; o < 7; ++o)
        local.block<9, 9>(offset, offset) += gv[map.controlled[side][o]] * map.hessians[side][o];
    const Eigen::Index m = local.rows();
    for (Eigen::Index c = 0; c < m; ++c)
      for (Eigen::Index r = 0; r < m; ++r)
        triplets.emplace_back(map.global[r], map.global[c], local(r, c));
  }
}

Eigen::SparseMatrix<double> RodLinkage::hessian(const std::vector<Eigen::VectorXd>* forces) const {
  std::vector<Eigen::Triplet<double>> triplets;
  hessian_triplets(triplets, forces);
  Eigen::SparseMatrix<double> h(num_dofs_, num_dofs_);
  h.setFromTriplets(triplets.begin(), triplets.end());
  return h;
}

Eigen::VectorXd RodLinkage::full_velocity(int s, const Eigen::VectorXd& reduced_velocity) const {
  const ElasticRod& rod = rods_[s];
  const std::vector<int>& slot = slots_[s];
  Eigen::VectorXd out(rod.num_dofs());
  for (int k = 0; k < rod.num_dofs(); ++k) out[k] = slot[k] >= 0 ? reduced_velocity[slot[k]] : 0.0;
  // A joint's terminal edge: the directional derivative of terminal() along
  // its parameters' velocity (forward mode, one direction).
  using D = Dual1<1>;
  const SegmentTopology& seg = topology_.segments[s];
  for (int side = 0; side < 2; ++side) {
    if (seg.joint[side] < 0) continue;
    const int offset = joint_offset_[seg.joint[side]];
    std::array<D, 9> q;
    for (int k = 0; k < 9; ++k) {
      q[k] = D(joints_[seg.joint[side]].params()[k]);
      q[k].g[0] = reduced_velocity[offset + k];
    }
    const TerminalEdge<D> t = terminal(s, side, q.data());
    const int edge = terminal_edge_index(rod, side);
    const int first = ElasticRod::node_dof(edge), second = ElasticRod::node_dof(edge + 1);
    out.segment<3>(first) << t.first.x.g[0], t.first.y.g[0], t.first.z.g[0];
    out.segment<3>(second) << t.second.x.g[0], t.second.y.g[0], t.second.z.g[0];
    out[rod.theta_dof(edge)] = t.theta.g[0];
  }
  return out;
}

Eigen::MatrixXd RodLinkage::full_velocities(int s,
                                            const Eigen::MatrixXd& reduced_velocities) const {
  const LocalMap map = local_map(s, false);
  Eigen::MatrixXd local(map.global.size(), reduced_velocities.cols());
  for (size_t k = 0; k < map.global.size(); ++k)
    local.row(static_cast<Eigen::Index>(k)) = reduced_velocities.row(map.global[k]);
  return map.jacobian * local;
}

Eigen::VectorXd RodLinkage::lumped_mass(bool unit_density) const {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(num_dofs_);
  for (int s = 0; s < num_segments(); ++s) {
    const Eigen::VectorXd mv = rods_[s].lumped_mass(unit_density);
    const LocalMap map = local_map(s, false);
    const Eigen::VectorXd local =
        (map.jacobian.array().square().colwise() * mv.array()).colwise().sum();
    for (size_t k = 0; k < map.global.size(); ++k) m[map.global[k]] += local[k];
  }
  return m;
}

}  // namespace xshell
