#include "topology.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <deque>
#include <string>

#include "math/rotation.hpp"
#include "model_error.hpp"

namespace xshell {

namespace {

struct Incidence {
  int segment;
  int end;               // 0: the segment starts here, 1: it ends here
  Eigen::Vector3d away;  // unit direction from the vertex into the segment
};

struct EndRef {
  int segment = -1, end = -1;
  bool valid() const { return segment >= 0; }
};

// "vertex v", for messages.
std::string vertex_name(int v) { return "vertex " + std::to_string(v); }

// Pairs the straightest two incident segments (valence 3 and 4).
void pair_segments(const std::vector<Incidence>& inc, std::vector<std::array<EndRef, 2>>& partner) {
  const int n = static_cast<int>(inc.size());
  if (n < 3) return;
  int best_a = 0, best_b = 1;
  double best = 2.0;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      const double d = inc[a].away.dot(inc[b].away);
      if (d < best) {
        best = d;
        best_a = a;
        best_b = b;
      }
    }
  auto link = [&](int a, int b) {
    partner[inc[a].segment][inc[a].end] = {inc[b].segment, inc[b].end};
    partner[inc[b].segment][inc[b].end] = {inc[a].segment, inc[a].end};
  };
  link(best_a, best_b);
  if (n == 4) {
    int rest[2], k = 0;
    for (int a = 0; a < 4; ++a)
      if (a != best_a && a != best_b) rest[k++] = a;
    link(rest[0], rest[1]);
  }
}

// Chains of partnered segments, one per rod, each started from its lowest
// segment; rod_of_segment gets each segment's rod.
std::vector<RodChain> build_rods(int num_segments,
                                 const std::vector<std::array<EndRef, 2>>& partner,
                                 std::vector<int>& rod_of_segment) {
  std::vector<RodChain> rods;
  rod_of_segment.assign(num_segments, -1);
  for (int s0 = 0; s0 < num_segments; ++s0) {
    if (rod_of_segment[s0] >= 0) continue;
    // Walk backwards from s0's start to the chain's first segment.
    int first = s0, first_entry = 0;  // entered at its start: forward
    for (EndRef p = partner[s0][0]; p.valid();) {
      if (p.segment == s0) break;  // closed loop
      first = p.segment;
      first_entry =
          1 - p.end;  // we came into s0 through p.end, so the rod enters p at the other end
      p = partner[p.segment][first_entry];
    }
    RodChain chain;
    int s = first, entry = first_entry;
    while (true) {
      rod_of_segment[s] = static_cast<int>(rods.size());
      chain.segments.push_back(s);
      chain.forward.push_back(entry == 0);
      const EndRef next = partner[s][1 - entry];
      if (!next.valid() || rod_of_segment[next.segment] >= 0) break;
      s = next.segment;
      entry = next.end;
    }
    rods.push_back(std::move(chain));
  }
  return rods;
}

// Normal of the best-fit plane through v, its neighbours and theirs (any
// perpendicular of fallback_tangent when they lie on a line).
Eigen::Vector3d best_fit_normal(const LineGraph& graph,
                                const std::vector<std::vector<int>>& neighbours, int v,
                                const Eigen::Vector3d& fallback_tangent) {
  std::vector<int> points = {v};
  for (int a : neighbours[v]) {
    points.push_back(a);
    for (int b : neighbours[a]) points.push_back(b);
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int p : points) mean += graph.vertices[p];
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int p : points) cov += (graph.vertices[p] - mean) * (graph.vertices[p] - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d values = eig.eigenvalues();
  // A line-like neighbourhood has no plane: any normal to the rods will do.
  if (values[1] <= 1e-12 * std::max(values[2], 1e-300)) return any_perpendicular(fallback_tangent);
  return eig.eigenvectors().col(0);
}

// Segment table (end vertices, lengths) and, per vertex, its incident
// segment ends and its neighbouring vertices.
void collect_incidences(const LineGraph& graph, LinkageTopology& topo,
                        std::vector<std::vector<Incidence>>& incident,
                        std::vector<std::vector<int>>& neighbours) {
  const int nv = static_cast<int>(graph.vertices.size());
  const int ns = static_cast<int>(graph.edges.size());
  incident.assign(nv, {});
  neighbours.assign(nv, {});
  topo.segments.resize(ns);
  for (int s = 0; s < ns; ++s) {
    const auto [a, b] = graph.edges[s];
    const Eigen::Vector3d d = graph.vertices[b] - graph.vertices[a];
    topo.segments[s].vertex = {a, b};
    topo.segments[s].length = d.norm();
    incident[a].push_back({s, 0, d.normalized()});
    incident[b].push_back({s, 1, -d.normalized()});
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
}

// Rejects isolated vertices and vertices of valence above 4.
void check_valences(const std::vector<int>& valence) {
  for (int v = 0; v < static_cast<int>(valence.size()); ++v) {
    if (valence[v] == 0) throw ModelError(vertex_name(v) + " has no edges");
    if (valence[v] > 4)
      throw ModelError(vertex_name(v) + " has valence " + std::to_string(valence[v]) +
                       "; a scissor joint joins at most 4 segments");
  }
}

// Glues the segments into rods (straightest pairs at every vertex) and
// records each segment's rod.
void glue_rods(const std::vector<std::vector<Incidence>>& incident, LinkageTopology& topo) {
  const int ns = static_cast<int>(topo.segments.size());
  std::vector<std::array<EndRef, 2>> partner(ns);
  for (const std::vector<Incidence>& inc : incident) pair_segments(inc, partner);
  std::vector<int> rod_of_segment;
  topo.rods = build_rods(ns, partner, rod_of_segment);
  for (int s = 0; s < ns; ++s) topo.segments[s].rod = rod_of_segment[s];
}

// +1 when segment s runs along its rod's direction, -1 otherwise.
int rod_direction(const LinkageTopology& topo, int s) {
  const RodChain& rod = topo.rods[topo.segments[s].rod];
  for (size_t k = 0; k < rod.segments.size(); ++k)
    if (rod.segments[k] == s) return rod.forward[k] ? 1 : -1;
  return 1;
}

// The joint at vertex v (valence 2 or more) with its two rods and segment
// ends; tangent gets its unit rod tangents, not yet oriented.
JointTopology make_joint(const LinkageTopology& topo, int v, const std::vector<Incidence>& incident,
                         std::array<Eigen::Vector3d, 2>& tangent) {
  JointTopology joint;
  joint.vertex = v;
  int label = 0;
  for (const Incidence& in : incident) {
    const int rod = topo.segments[in.segment].rod;
    int slot = (joint.rod[0] == rod) ? 0 : (joint.rod[1] == rod ? 1 : -1);
    if (slot < 0) {
      if (label > 1) throw ModelError(vertex_name(v) + ": more than two rods meet at this joint");
      slot = label++;
      joint.rod[slot] = rod;
      tangent[slot] = Eigen::Vector3d::Zero();
    }
    // Rod-oriented direction of the segment at this vertex.
    const Eigen::Vector3d seg_dir = in.end == 0 ? in.away : Eigen::Vector3d(-in.away);
    const int forward = rod_direction(topo, in.segment);
    tangent[slot] += forward * seg_dir;
    joint.ends[slot].push_back({in.segment, in.end == 0, forward});
  }
  if (joint.rod[0] == joint.rod[1] || label != 2)
    throw ModelError(vertex_name(v) + ": a rod passes through this joint twice");
  for (auto& t : tangent) t.normalize();
  joint.collinear =
      tangent[0].cross(tangent[1]).norm() < std::sin(kCollinearDegrees * M_PI / 180.0);
  return joint;
}

// Joints in vertex order, and their base (unoriented) tangents.
std::vector<std::array<Eigen::Vector3d, 2>> build_joints(
    const std::vector<std::vector<Incidence>>& incident, LinkageTopology& topo) {
  const int nv = static_cast<int>(incident.size());
  topo.joint_of_vertex.assign(nv, -1);
  std::vector<std::array<Eigen::Vector3d, 2>> base_tangent;
  for (int v = 0; v < nv; ++v) {
    if (topo.valence[v] < 2) continue;
    std::array<Eigen::Vector3d, 2> tangent;
    JointTopology joint = make_joint(topo, v, incident[v], tangent);
    topo.joint_of_vertex[v] = static_cast<int>(topo.joints.size());
    topo.joints.push_back(std::move(joint));
    base_tangent.push_back(tangent);
  }
  return base_tangent;
}

// Raw normal of collinear joint j: the sign-aligned sum of the normals of
// the nearest regular joints (breadth first through the graph), else that
// of the best-fit plane, never along the rods.
Eigen::Vector3d collinear_normal(const LineGraph& graph, const LinkageTopology& topo,
                                 const std::vector<std::vector<int>>& neighbours,
                                 const std::vector<Eigen::Vector3d>& normal,
                                 const Eigen::Vector3d& t, int j) {
  const int v0 = topo.joints[j].vertex;
  std::vector<int> distance(graph.vertices.size(), -1);
  std::deque<int> queue = {v0};
  distance[v0] = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int found_at = -1;
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    if (found_at >= 0 && distance[v] > found_at) break;
    const int k = topo.joint_of_vertex[v];
    if (v != v0 && k >= 0 && !topo.joints[k].collinear) {
      found_at = distance[v];
      sum += (sum.dot(normal[k]) < 0.0 ? -1.0 : 1.0) * normal[k];
      continue;
    }
    for (int w : neighbours[v])
      if (distance[w] < 0) {
        distance[w] = distance[v] + 1;
        queue.push_back(w);
      }
  }
  Eigen::Vector3d n = (found_at >= 0 && sum.norm() > 1e-8)
                          ? Eigen::Vector3d(sum.normalized())
                          : best_fit_normal(graph, neighbours, v0, t);
  // The rods at a collinear joint must lie in its plane: a normal along
  // them is no normal.
  if (std::abs(n.dot(t)) > 0.99) n = best_fit_normal(graph, neighbours, v0, t);
  if (std::abs(n.dot(t)) > 0.99) n = any_perpendicular(t);
  return n;
}

// Raw normals: regular joints from their rods, collinear ones from the
// nearest regular joints (sign-aligned), else from a best-fit plane.
std::vector<Eigen::Vector3d> raw_normals(
    const LineGraph& graph, const LinkageTopology& topo,
    const std::vector<std::vector<int>>& neighbours,
    const std::vector<std::array<Eigen::Vector3d, 2>>& base_tangent) {
  const int nj = static_cast<int>(topo.joints.size());
  std::vector<Eigen::Vector3d> normal(nj);
  for (int j = 0; j < nj; ++j)
    if (!topo.joints[j].collinear)
      normal[j] = base_tangent[j][0].cross(base_tangent[j][1]).normalized();
  for (int j = 0; j < nj; ++j)
    if (topo.joints[j].collinear)
      normal[j] = collinear_normal(graph, topo, neighbours, normal, base_tangent[j][0], j);
  return normal;
}

// Per joint, the joints that share a segment with it (in segment order).
std::vector<std::vector<int>> joint_neighbours(const LinkageTopology& topo) {
  std::vector<std::vector<int>> out(topo.joints.size());
  for (const auto& seg : topo.segments) {
    const int a = topo.joint_of_vertex[seg.vertex[0]], b = topo.joint_of_vertex[seg.vertex[1]];
    if (a >= 0 && b >= 0) {
      out[a].push_back(b);
      out[b].push_back(a);
    }
  }
  return out;
}

// Orients the normals consistently, breadth first through the joints, and
// rejects a linkage where they cannot agree (non-orientable): there no
// labelling opens all joints the same way.
void orient_normals(const LinkageTopology& topo, const std::vector<std::vector<int>>& adjacent,
                    std::vector<Eigen::Vector3d>& normal) {
  const int nj = static_cast<int>(normal.size());
  std::vector<bool> oriented(nj, false);
  for (int root = 0; root < nj; ++root) {
    if (oriented[root]) continue;
    oriented[root] = true;
    std::deque<int> queue = {root};
    while (!queue.empty()) {
      const int j = queue.front();
      queue.pop_front();
      for (int k : adjacent[j]) {
        if (oriented[k]) continue;
        if (normal[k].dot(normal[j]) < 0.0) normal[k] = -normal[k];
        oriented[k] = true;
        queue.push_back(k);
      }
    }
  }
  for (int j = 0; j < nj; ++j)
    for (int k : adjacent[j])
      if (normal[j].dot(normal[k]) < -0.5)
        throw ModelError(
            vertex_name(topo.joints[j].vertex) + " and " + vertex_name(topo.joints[k].vertex) +
            ": the joint normals cannot be oriented consistently (non-orientable linkage)");
}

// Directions of the rods (+1: as built, -1: reversed), breadth first through
// the regular joints. At a joint with rods r, q and base tangents tr, tq,
// s = sign((tr x tq) . n). Giving each rod a family (A or B), the same at
// all its joints, the directions o with (t_A x t_B) . n > 0 satisfy
// o_q = o_r s if r is A and -o_r s if r is B. Where a rod crosses another
// twice (curved rods), the two crossings may ask for opposite directions:
// the first one reached wins, and the joint's labels follow its own
// geometry (label_joint).
std::vector<int> rod_directions(const LinkageTopology& topo,
                                const std::vector<std::array<Eigen::Vector3d, 2>>& base_tangent,
                                const std::vector<Eigen::Vector3d>& normal) {
  const int nr = static_cast<int>(topo.rods.size());
  std::vector<int> family(nr, -1), direction(nr, 1);
  std::vector<std::vector<int>> joints_of_rod(nr);
  for (int j = 0; j < static_cast<int>(topo.joints.size()); ++j)
    if (!topo.joints[j].collinear)
      for (int r : topo.joints[j].rod) joints_of_rod[r].push_back(j);
  for (int root = 0; root < nr; ++root) {
    if (family[root] >= 0) continue;
    family[root] = 0;
    std::deque<int> queue = {root};
    while (!queue.empty()) {
      const int r = queue.front();
      queue.pop_front();
      for (int j : joints_of_rod[r]) {
        const JointTopology& joint = topo.joints[j];
        const int slot_r = joint.rod[0] == r ? 0 : 1;
        const int q = joint.rod[1 - slot_r];
        if (family[q] >= 0) continue;
        const double triple =
            base_tangent[j][slot_r].cross(base_tangent[j][1 - slot_r]).dot(normal[j]);
        const int s = triple > 0.0 ? 1 : -1;
        family[q] = 1 - family[r];
        direction[q] = (family[r] == 0 ? 1 : -1) * direction[r] * s;
        queue.push_back(q);
      }
    }
  }
  return direction;
}

// Reverses the rods whose direction is -1.
void apply_rod_directions(const std::vector<int>& direction, std::vector<RodChain>& rods) {
  for (size_t r = 0; r < rods.size(); ++r) {
    if (direction[r] > 0) continue;
    RodChain& rod = rods[r];
    std::reverse(rod.segments.begin(), rod.segments.end());
    std::reverse(rod.forward.begin(), rod.forward.end());
    for (size_t k = 0; k < rod.forward.size(); ++k) rod.forward[k] = !rod.forward[k];
  }
}

// Joint j's final labels (A, B with (t_A x t_B) . n > 0), tangents, normal
// and opening angle, and the joint, labels and signs of its segments' ends.
void label_joint(int j, const std::vector<int>& direction, std::array<Eigen::Vector3d, 2> base,
                 const Eigen::Vector3d& n, LinkageTopology& topo) {
  JointTopology& joint = topo.joints[j];
  for (int slot = 0; slot < 2; ++slot) {
    const int d = direction[joint.rod[slot]];
    base[slot] *= d;
    for (SegmentEnd& end : joint.ends[slot]) end.sign *= d;
  }
  std::array<Eigen::Vector3d, 2> t;
  for (int slot = 0; slot < 2; ++slot) t[slot] = (base[slot] - base[slot].dot(n) * n).normalized();
  if (t[0].cross(t[1]).dot(n) < 0.0) {
    std::swap(joint.ends[0], joint.ends[1]);
    std::swap(joint.rod[0], joint.rod[1]);
    std::swap(t[0], t[1]);
  }
  joint.tangent = t;
  joint.normal = n;
  joint.opening_angle = std::atan2(t[0].cross(t[1]).dot(n), t[0].dot(t[1]));
  if (!(joint.opening_angle > 0.0 && joint.opening_angle < M_PI))
    throw ModelError(vertex_name(joint.vertex) + ": its two rods are exactly collinear");
  for (int slot = 0; slot < 2; ++slot)
    for (const SegmentEnd& end : joint.ends[slot]) {
      SegmentTopology& seg = topo.segments[end.segment];
      const int side = end.at_start ? 0 : 1;
      seg.joint[side] = j;
      seg.label[side] = slot;
      seg.sign[side] = end.sign;
    }
}

}  // namespace

LinkageTopology build_topology(const LineGraph& graph) {
  LinkageTopology topo;
  topo.valence = valences(graph);
  std::vector<std::vector<Incidence>> incident;
  std::vector<std::vector<int>> neighbours;
  collect_incidences(graph, topo, incident, neighbours);
  check_valences(topo.valence);
  glue_rods(incident, topo);
  const std::vector<std::array<Eigen::Vector3d, 2>> base_tangent = build_joints(incident, topo);
  std::vector<Eigen::Vector3d> normal = raw_normals(graph, topo, neighbours, base_tangent);
  orient_normals(topo, joint_neighbours(topo), normal);
  const std::vector<int> direction = rod_directions(topo, base_tangent, normal);
  apply_rod_directions(direction, topo.rods);
  for (int j = 0; j < static_cast<int>(topo.joints.size()); ++j)
    label_joint(j, direction, base_tangent[j], normal[j], topo);
  return topo;
}

}  // namespace xshell
