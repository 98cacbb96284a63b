#include "rod_linkage.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "edge_vector_conversion.hpp"
#include "model_error.hpp"
#include "segment_parallel.hpp"

namespace xshell {

namespace {
std::string degrees_text(double degrees) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", degrees);
  return buffer;
}

// Segments' energies summed in segment order: the same bits on any number
// of threads.
RodEnergy sum_in_order(const std::vector<RodEnergy>& parts) {
  RodEnergy e;
  for (const RodEnergy& part : parts) e += part;
  return e;
}

// Theta that turns an edge's reference frame so that d2 = n.
double theta_for_normal(const Frame<double>& ref, const Eigen::Vector3d& n) {
  return std::atan2(-n.dot(ref.d1.values()), n.dot(ref.d2.values()));
}

// Rejects fewer than kMinSubdivisions edges per segment, a list of segment
// materials that is not one per segment, and a clamped end that is no free
// rod end.
void check_options(const LinkageOptions& options, const LinkageTopology& topology) {
  const int n = options.subdivisions;
  const int num_segments = static_cast<int>(topology.segments.size());
  if (n < kMinSubdivisions)
    throw ModelError("subdivisions must be at least " + std::to_string(kMinSubdivisions) +
                     ", got " + std::to_string(n));
  if (!options.segment_materials.empty() &&
      static_cast<int>(options.segment_materials.size()) != num_segments)
    throw ModelError("segment materials: " + std::to_string(options.segment_materials.size()) +
                     " given for " + std::to_string(num_segments) + " segments");
  const int nv = static_cast<int>(topology.joint_of_vertex.size());
  for (int v : options.clamped_ends)
    if (v < 0 || v >= nv || topology.joint_of_vertex[v] >= 0)
      throw ModelError("vertex " + std::to_string(v) +
                       " is no free rod end (valence 1), so it cannot be a clamped end");
}

// Whether `vertex` is a clamped free end (options.clamped_ends is sorted).
bool clamped(const LinkageOptions& options, int vertex) {
  return std::binary_search(options.clamped_ends.begin(), options.clamped_ends.end(), vertex);
}

// Per end of a segment, whether its end edge is centred on the vertex: at a
// joint and at a clamped free end (docs/model.md section 3.2).
std::array<bool, 2> centred_ends(const SegmentTopology& seg, const LinkageOptions& options) {
  return {seg.joint[0] >= 0 || clamped(options, seg.vertex[0]),
          seg.joint[1] >= 0 || clamped(options, seg.vertex[1])};
}

// The uniform edge length that fills the segment: L / (n - k / 2), k its
// number of centred ends (each reaches half an edge past its vertex).
double nominal_edge_length(const SegmentTopology& seg, const LinkageOptions& options) {
  const std::array<bool, 2> centred = centred_ends(seg, options);
  const int centred_count = centred[0] + centred[1];
  return seg.length / (options.subdivisions - 0.5 * centred_count);
}

// The joints in topology order, their terminal edges as long as the uniform
// edge length that fills each segment allows (the smallest over each rod's
// segments there).
std::vector<Joint> build_joints(const LineGraph& graph, const LinkageTopology& topology,
                                const LinkageOptions& options) {
  const int ns = static_cast<int>(topology.segments.size());
  std::vector<double> edge_length(ns);
  for (int s = 0; s < ns; ++s) edge_length[s] = nominal_edge_length(topology.segments[s], options);
  std::vector<Joint> joints;
  for (const JointTopology& jt : topology.joints) {
    double l[2];
    for (int x = 0; x < 2; ++x) {
      l[x] = std::numeric_limits<double>::infinity();
      for (const SegmentEnd& end : jt.ends[x]) l[x] = std::min(l[x], edge_length[end.segment]);
    }
    if (options.joint_kind == JointKind::EdgeVectors &&
        nearly_parallel(jt.tangent[0], jt.tangent[1])) {
      const double angle = std::min(jt.opening_angle, M_PI - jt.opening_angle) * 180.0 / M_PI;
      throw ModelError(
          "vertex " + std::to_string(jt.vertex) + ": its rods are " + degrees_text(angle) +
          " degrees from parallel; edge-vector joints need at least " +
          degrees_text(kMinEdgeVectorAngleDegrees) +
          " degree (their normal e_A x e_B is ill-defined there): use rotation joints");
    }
    joints.emplace_back(graph.vertices[jt.vertex], jt.tangent[0], jt.tangent[1], jt.normal, l[0],
                        l[1], options.joint_kind);
  }
  return joints;
}

// The end edge of segment seg at `side` when it is centred on the vertex:
// the joint's terminal edge (times the segment's sign), or at a clamped free
// end the nominal edge along the segment.
Eigen::Vector3d centred_end_edge(const LineGraph& graph, const SegmentTopology& seg,
                                 const std::vector<Joint>& joints, const LinkageOptions& options,
                                 int side) {
  if (seg.joint[side] >= 0) return seg.sign[side] * joints[seg.joint[side]].edge(seg.label[side]);
  const Eigen::Vector3d along = graph.vertices[seg.vertex[1]] - graph.vertices[seg.vertex[0]];
  return nominal_edge_length(seg, options) / along.norm() * along;
}

// The n + 1 nodes of segment s: its end edges at joints and at clamped free
// ends centred on their vertices, another free end's node on its vertex, the
// others evenly spaced between.
std::vector<Eigen::Vector3d> segment_nodes(const LineGraph& graph, const SegmentTopology& seg,
                                           const std::vector<Joint>& joints,
                                           const LinkageOptions& options, int s) {
  const int n = options.subdivisions;
  const std::array<bool, 2> centred = centred_ends(seg, options);
  std::vector<Eigen::Vector3d> nodes(n + 1);
  int first_free = 0, last_free = n;
  if (centred[0]) {
    const Eigen::Vector3d e = centred_end_edge(graph, seg, joints, options, 0);
    nodes[0] = graph.vertices[seg.vertex[0]] - 0.5 * e;
    nodes[1] = graph.vertices[seg.vertex[0]] + 0.5 * e;
    first_free = 1;
  } else {
    nodes[0] = graph.vertices[seg.vertex[0]];
  }
  if (centred[1]) {
    const Eigen::Vector3d e = centred_end_edge(graph, seg, joints, options, 1);
    nodes[n - 1] = graph.vertices[seg.vertex[1]] - 0.5 * e;
    nodes[n] = graph.vertices[seg.vertex[1]] + 0.5 * e;
    last_free = n - 1;
  } else {
    nodes[n] = graph.vertices[seg.vertex[1]];
  }
  for (int k = first_free + 1; k < last_free; ++k) {
    const double u = double(k - first_free) / double(last_free - first_free);
    nodes[k] = (1.0 - u) * nodes[first_free] + u * nodes[last_free];
  }
  for (int j = 0; j < n; ++j)
    if ((nodes[j + 1] - nodes[j]).norm() <= 1e-12 * seg.length)
      throw ModelError("segment " + std::to_string(s) + " (vertices " +
                       std::to_string(seg.vertex[0]) + "-" + std::to_string(seg.vertex[1]) +
                       ") is too short for its centred end edges (at joints or clamps)");
  return nodes;
}

// Thetas of the rod's n edges that put d2 on the joint normals at its
// terminal edges, linear in arc length (edge midpoints) between the two
// (constant when one end or both are free).
std::vector<double> normal_aligned_thetas(const ElasticRod& rod, const SegmentTopology& seg,
                                          const std::vector<Joint>& joints, int n) {
  std::vector<double> thetas(n, 0.0);
  double theta_start = 0.0, theta_end = 0.0;
  if (seg.joint[0] >= 0)
    theta_start = theta_for_normal(rod.reference_frame(0), joints[seg.joint[0]].normal());
  if (seg.joint[1] >= 0)
    theta_end = theta_for_normal(rod.reference_frame(n - 1), joints[seg.joint[1]].normal());
  if (seg.joint[0] < 0) theta_start = theta_end;
  if (seg.joint[1] < 0) theta_end = theta_start;
  theta_end = theta_start + std::remainder(theta_end - theta_start, 2.0 * M_PI);
  std::vector<double> arc(n, 0.0);
  for (int j = 1; j < n; ++j)
    arc[j] = arc[j - 1] + 0.5 * (rod.edge(j - 1).norm() + rod.edge(j).norm());
  for (int j = 0; j < n; ++j)
    thetas[j] = theta_start + (theta_end - theta_start) * arc[j] / arc[n - 1];
  return thetas;
}

// Segment s as a rod: nodes, twist-free frames, thetas putting d2 on the
// joint normals, rest state, and half the stretching and mass of an end edge
// centred on its vertex (at a joint the segment on the other side owns the
// other half; at a clamp it lies outside the rod).
ElasticRod build_segment(const LineGraph& graph, const SegmentTopology& seg,
                         const std::vector<Joint>& joints, const Material& material,
                         const LinkageOptions& options, int s) {
  const int n = options.subdivisions;
  const std::vector<Eigen::Vector3d> nodes = segment_nodes(graph, seg, joints, options, s);
  const Eigen::Vector3d start_d1 =
      seg.joint[0] >= 0 ? Eigen::Vector3d(joints[seg.joint[0]].normal().cross(nodes[1] - nodes[0]))
                        : Eigen::Vector3d::Zero();
  ElasticRod rod(nodes, xshell::stiffness(material), seg.joint[0] >= 0 ? &start_d1 : nullptr);
  rod.set_configuration(nodes, normal_aligned_thetas(rod, seg, joints, n));
  rod.update_source_frames();
  rod.set_rest_state_from_current();
  if (options.rest_shape == RestShape::Straight) rod.set_rest_straight();
  const std::array<bool, 2> centred = centred_ends(seg, options);
  if (centred[0]) rod.set_stretching_share(0, 0.5);
  if (centred[1]) rod.set_stretching_share(n - 1, 0.5);
  return rod;
}
}  // namespace

RodLinkage::RodLinkage(const LineGraph& graph, const LinkageOptions& options)
    : graph_(graph), options_(options), topology_(build_topology(graph)) {
  const int ns = static_cast<int>(topology_.segments.size());
  std::vector<int>& clamps = options_.clamped_ends;
  std::sort(clamps.begin(), clamps.end());
  clamps.erase(std::unique(clamps.begin(), clamps.end()), clamps.end());
  check_options(options_, topology_);
  joints_ = build_joints(graph, topology_, options_);
  for (int s = 0; s < ns; ++s)
    rods_.push_back(
        build_segment(graph, topology_.segments[s], joints_, segment_material(s), options_, s));
  if (!options_.segment_rest_lengths.empty())
    set_segment_rest_lengths(options_.segment_rest_lengths);
  number_unknowns();
  // The joints reproduce the terminal edges and thetas just built.
  set_dofs(dofs());
  record_theta_hints();
  for (const ElasticRod& rod : rods_) input_segment_dofs_.push_back(rod.dofs());
}

void RodLinkage::number_unknowns() {
  const int n = options_.subdivisions;
  const int ns = static_cast<int>(rods_.size());
  slots_.resize(ns);
  segment_offset_.resize(ns);
  int next = 0;
  for (int s = 0; s < ns; ++s) {
    const SegmentTopology& seg = topology_.segments[s];
    const ElasticRod& rod = rods_[s];
    segment_offset_[s] = next;
    std::vector<int>& slot = slots_[s];
    slot.assign(rod.num_dofs(), 0);
    auto control = [&](int side, int node_a, int theta) {
      for (int c = 0; c < 3; ++c) {
        slot[ElasticRod::node_dof(node_a) + c] = -1 - (7 * side + c);
        slot[ElasticRod::node_dof(node_a + 1) + c] = -1 - (7 * side + 3 + c);
      }
      slot[rod.theta_dof(theta)] = -1 - (7 * side + 6);
    };
    if (seg.joint[0] >= 0) control(0, 0, 0);
    if (seg.joint[1] >= 0) control(1, n - 1, n - 1);
    for (int k = 0; k < 3 * (n + 1); ++k)
      if (slot[k] == 0) slot[k] = next++;
    for (int j = 0; j < n; ++j)
      if (slot[rod.theta_dof(j)] == 0) slot[rod.theta_dof(j)] = next++;
  }
  joint_offset_.resize(joints_.size());
  for (size_t j = 0; j < joints_.size(); ++j) {
    joint_offset_[j] = next;
    next += 9;
  }
  num_dofs_ = next;
}

Eigen::VectorXd RodLinkage::dofs() const {
  Eigen::VectorXd r(num_dofs_);
  for (int s = 0; s < num_segments(); ++s) {
    const ElasticRod& rod = rods_[s];
    const std::vector<int>& slot = slots_[s];
    for (int k = 0; k < rod.num_nodes(); ++k)
      for (int c = 0; c < 3; ++c)
        if (slot[ElasticRod::node_dof(k) + c] >= 0)
          r[slot[ElasticRod::node_dof(k) + c]] = rod.nodes()[k][c];
    for (int j = 0; j < rod.num_edges(); ++j)
      if (slot[rod.theta_dof(j)] >= 0) r[slot[rod.theta_dof(j)]] = rod.thetas()[j];
  }
  for (int j = 0; j < num_joints(); ++j) r.segment<9>(joint_offset_[j]) = joints_[j].params();
  return r;
}

TerminalEdge<double> RodLinkage::terminal(int s, int side) const {
  return terminal(s, side, joints_[topology_.segments[s].joint[side]].params().data());
}

void RodLinkage::record_theta_hints() {
  theta_hints_.resize(rods_.size());
  for (size_t s = 0; s < rods_.size(); ++s)
    theta_hints_[s] = {rods_[s].thetas().front(), rods_[s].thetas().back()};
}

void RodLinkage::check_joint_params(const Eigen::VectorXd& r) const {
  if (r.size() != num_dofs_) throw std::invalid_argument("RodLinkage::set_dofs: wrong size");
  for (int j = 0; j < num_joints(); ++j) {
    const std::string problem = joints_[j].check_params(r.segment<9>(joint_offset_[j]));
    if (!problem.empty())
      throw std::domain_error("joint at vertex " + std::to_string(topology_.joints[j].vertex) +
                              ": " + problem);
  }
}

Eigen::VectorXd RodLinkage::segment_dofs_at(int s, const Eigen::VectorXd& r) const {
  const ElasticRod& rod = rods_[s];
  Eigen::VectorXd q = rod.dofs();
  for (int k = 0; k < q.size(); ++k)
    if (slots_[s][k] >= 0) q[k] = r[slots_[s][k]];
  for (int side = 0; side < 2; ++side) {
    const int j = topology_.segments[s].joint[side];
    if (j < 0) continue;
    const TerminalEdge<double> t = terminal(s, side, r.data() + joint_offset_[j]);
    const int node = terminal_edge_index(rod, side);
    q.segment<3>(ElasticRod::node_dof(node)) = t.first.values();
    q.segment<3>(ElasticRod::node_dof(node + 1)) = t.second.values();
    q[rod.theta_dof(node)] = t.theta;
  }
  return q;
}

void RodLinkage::set_dofs(const Eigen::VectorXd& r, RodEnergy* energy) {
  check_joint_params(r);
  for (int j = 0; j < num_joints(); ++j) joints_[j].set_params(r.segment<9>(joint_offset_[j]));
  std::vector<RodEnergy> parts(energy ? rods_.size() : 0);
  for_each_segment(num_segments(), [&](int s) {
    ElasticRod& rod = rods_[s];
    rod.set_dofs(segment_dofs_at(s, r));
    if (energy) parts[s] = rod.energy();
  });
  if (energy) *energy = sum_in_order(parts);
}

std::vector<std::vector<Eigen::Vector3d>> RodLinkage::nodes_at(const Eigen::VectorXd& r) const {
  check_joint_params(r);
  std::vector<std::vector<Eigen::Vector3d>> out(rods_.size());
  for_each_segment(num_segments(), [&](int s) {
    const Eigen::VectorXd q = segment_dofs_at(s, r);
    std::vector<Eigen::Vector3d>& nodes = out[static_cast<size_t>(s)];
    nodes.resize(static_cast<size_t>(rods_[s].num_nodes()));
    for (int i = 0; i < rods_[s].num_nodes(); ++i)
      nodes[static_cast<size_t>(i)] = q.segment<3>(ElasticRod::node_dof(i));
  });
  return out;
}

LinkageState RodLinkage::state() const {
  LinkageState out;
  for (const ElasticRod& rod : rods_)
    out.segments.push_back({rod.nodes(), rod.thetas(), rod.source_frames(), rod.twist_hints()});
  for (const Joint& joint : joints_)
    out.joints.push_back({joint.kind(), joint.params(), joint.reference_frame()});
  return out;
}

void RodLinkage::restore(const LinkageState& state) {
  if (state.segments.size() != rods_.size() || state.joints.size() != joints_.size())
    throw std::invalid_argument("the state has " + std::to_string(state.segments.size()) +
                                " segments and " + std::to_string(state.joints.size()) +
                                " joints, the linkage " + std::to_string(rods_.size()) + " and " +
                                std::to_string(joints_.size()));
  for (size_t s = 0; s < rods_.size(); ++s) {
    const SegmentState& seg = state.segments[s];
    rods_[s].restore(seg.nodes, seg.thetas, seg.source_frames, seg.twist_hints);
  }
  for (size_t j = 0; j < joints_.size(); ++j) {
    const JointState& js = state.joints[j];
    Joint saved(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                Eigen::Vector3d::UnitZ(), 1.0, 1.0, js.kind);
    saved.set_reference_frame(js.reference_frame);
    saved.set_params(js.params);
    try {
      joints_[j] = convert_joint(saved, options_.joint_kind);
    } catch (const std::domain_error& e) {
      throw std::invalid_argument("joint at vertex " + std::to_string(topology_.joints[j].vertex) +
                                  ": " + e.what());
    }
  }
  // Recompute the joint-controlled variables from the joints, with the
  // restored thetas as branch hints.
  record_theta_hints();
  set_dofs(dofs());
}

RodLinkage::FreeEnd RodLinkage::free_end(int vertex) const {
  for (int s = 0; s < num_segments(); ++s)
    for (int side = 0; side < 2; ++side)
      if (topology_.segments[s].vertex[side] == vertex && topology_.segments[s].joint[side] < 0) {
        const int n = rods_[s].num_edges();
        FreeEnd f;
        f.segment = s;
        f.at_start = side == 0;
        f.clamped = clamped(options_, vertex);
        f.end_node = f.at_start ? 0 : n;
        f.next_node = f.at_start ? 1 : n - 1;
        f.edge = f.at_start ? 0 : n - 1;
        return f;
      }
  throw std::invalid_argument("vertex " + std::to_string(vertex) + " is not a free end");
}

Eigen::Vector3d RodLinkage::vertex_position(int vertex) const {
  const int j = topology_.joint_of_vertex[vertex];
  if (j >= 0) return joints_[j].position();
  const FreeEnd f = free_end(vertex);
  const std::vector<Eigen::Vector3d>& nodes = rods_[f.segment].nodes();
  if (f.clamped) return 0.5 * (nodes[f.end_node] + nodes[f.next_node]);
  return nodes[f.end_node];
}

void RodLinkage::update_source_frames() {
  for_each_segment(num_segments(), [&](int s) { rods_[s].update_source_frames(); });
  record_theta_hints();
}

void RodLinkage::fold_joints() {
  for (Joint& joint : joints_) joint.fold();
}

RodEnergy RodLinkage::energy() const {
  std::vector<RodEnergy> parts(rods_.size());
  for_each_segment(num_segments(), [&](int s) { parts[s] = rods_[s].energy(); });
  return sum_in_order(parts);
}

}  // namespace xshell
