#include "linkage/fabrication.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace xshell {

namespace {

// One rest edge of a rod, in rod order; `joint` sits at its midpoint (-1:
// none).
struct RodEdge {
  double length = 0.0;
  int joint = -1;
};

// The rod's rest edges in rod order, each terminal edge shared by two of its
// segments (at a joint it passes through) once.
std::vector<RodEdge> rod_edges(const RodLinkage& linkage, const RodChain& chain, bool closed) {
  const LinkageTopology& topo = linkage.topology();
  std::vector<RodEdge> edges;
  for (size_t k = 0; k < chain.segments.size(); ++k) {
    const int seg = chain.segments[k];
    const bool forward = chain.forward[k];
    const SegmentTopology& st = topo.segments[seg];
    std::vector<double> rest = linkage.segment(seg).rest_lengths();
    if (!forward) std::reverse(rest.begin(), rest.end());
    const int start_joint = st.joint[forward ? 0 : 1], end_joint = st.joint[forward ? 1 : 0];
    const int n = static_cast<int>(rest.size());  // >= 3: first and last edges differ
    // A later segment's first edge is the previous segment's last edge.
    for (int j = k > 0 ? 1 : 0; j < n; ++j)
      edges.push_back({rest[j], j == 0 ? start_joint : (j == n - 1 ? end_joint : -1)});
  }
  // A closed rod's last edge is its first edge again (the closing joint's).
  if (closed) edges.pop_back();
  return edges;
}

// Whether the rod returns to its first joint.
bool is_closed(const LinkageTopology& topo, const RodChain& chain) {
  if (chain.segments.size() < 2) return false;
  const SegmentTopology& first = topo.segments[chain.segments.front()];
  const SegmentTopology& last = topo.segments[chain.segments.back()];
  const int start = first.joint[chain.forward.front() ? 0 : 1];
  const int end = last.joint[chain.forward.back() ? 1 : 0];
  return start >= 0 && start == end;
}

// The OBJ vertex at the rod's start (at_start) or end when that is a free
// end, else -1.
int free_end_vertex(const LinkageTopology& topo, const RodChain& chain, bool at_start) {
  const size_t k = at_start ? 0 : chain.segments.size() - 1;
  const SegmentTopology& st = topo.segments[chain.segments[k]];
  // The rod-order start of a forward segment is its graph start.
  const int side = (at_start == static_cast<bool>(chain.forward[k])) ? 0 : 1;
  return st.joint[side] < 0 ? st.vertex[side] : -1;
}

// Label (0: A, 1: B) of rod r at joint j.
int label_at(const JointTopology& joint, int r) { return joint.rod[0] == r ? 0 : 1; }

// The family vote of the header: regular joints, then all, then the first.
RodFamily decide_family(const LinkageTopology& topo, int r, const std::vector<int>& joints) {
  if (joints.empty()) return RodFamily::A;
  int regular[2] = {0, 0}, all[2] = {0, 0};
  for (int j : joints) {
    const int label = label_at(topo.joints[j], r);
    ++all[label];
    if (!topo.joints[j].collinear) ++regular[label];
  }
  if (regular[0] != regular[1]) return regular[0] > regular[1] ? RodFamily::A : RodFamily::B;
  if (all[0] != all[1]) return all[0] > all[1] ? RodFamily::A : RodFamily::B;
  return label_at(topo.joints[joints.front()], r) == 0 ? RodFamily::A : RodFamily::B;
}

FabricationRod fabrication_rod(const RodLinkage& linkage, int r) {
  const LinkageTopology& topo = linkage.topology();
  const RodChain& chain = topo.rods[r];
  FabricationRod out;
  out.rod = r;
  out.closed = is_closed(topo, chain);
  out.section = linkage.segment_material(chain.segments.front()).section;
  const std::vector<RodEdge> edges = rod_edges(linkage, chain, out.closed);

  out.stations.push_back(
      {StationKind::End, out.closed ? -1 : free_end_vertex(topo, chain, true), -1, 0.0});
  std::vector<int> joints;
  double s = 0.0;
  for (const RodEdge& e : edges) {
    if (e.joint >= 0) {
      out.stations.push_back(
          {StationKind::Joint, topo.joints[e.joint].vertex, e.joint, s + 0.5 * e.length});
      joints.push_back(e.joint);
    }
    s += e.length;
  }
  out.length = s;
  out.stations.push_back(
      {StationKind::End, out.closed ? -1 : free_end_vertex(topo, chain, false), -1, s});

  out.family = decide_family(topo, r, joints);
  const int family_label = out.family == RodFamily::A ? 0 : 1;
  for (int j : joints)
    if (label_at(topo.joints[j], r) != family_label)
      out.other_label_vertices.push_back(topo.joints[j].vertex);
  return out;
}

}  // namespace

const char* family_name(RodFamily family) { return family == RodFamily::A ? "A" : "B"; }

FabricationData fabrication_data(const RodLinkage& linkage) {
  const LinkageTopology& topo = linkage.topology();
  FabricationData data;
  for (int r = 0; r < static_cast<int>(topo.rods.size()); ++r)
    data.rods.push_back(fabrication_rod(linkage, r));

  data.joints.resize(topo.joints.size());
  std::vector<std::array<int, 2>> found(topo.joints.size(), {0, 0});
  for (const FabricationRod& rod : data.rods)
    for (const RodStation& st : rod.stations) {
      if (st.kind != StationKind::Joint) continue;
      const int label = label_at(topo.joints[st.joint], rod.rod);
      data.joints[st.joint].s[label] = st.s;
      ++found[st.joint][label];
    }
  for (int j = 0; j < static_cast<int>(topo.joints.size()); ++j) {
    const JointTopology& jt = topo.joints[j];
    // Every joint lies on its two rods once each (header): a miss here is a
    // bug of the walk above, not of the input.
    if (found[j][0] != 1 || found[j][1] != 1)
      throw std::logic_error("fabrication data: joint at vertex " + std::to_string(jt.vertex) +
                             " is not a station of exactly its two rods");
    FabricationJoint& out = data.joints[j];
    out.joint = j;
    out.vertex = jt.vertex;
    out.valence = topo.valence[jt.vertex];
    out.rod = jt.rod;
    out.angle_input = jt.opening_angle;
    out.angle = linkage.joint(j).opening_angle();
  }
  return data;
}

}  // namespace xshell
