#include "linkage_snapshot.hpp"

namespace xshell {

namespace {
struct SegmentSample {
  std::vector<Eigen::Vector3d> nodes, d1, d2;
  std::vector<double> stretching, curvature, twist, bending, twisting;
};

// One segment's quantities in its own node order.
SegmentSample sample(const ElasticRod& rod) {
  SegmentSample s;
  s.nodes = rod.nodes();
  std::vector<double> stretch, bend, twist;
  rod.energy_per_element(stretch, bend, twist);
  const int n = rod.num_edges();
  for (int j = 0; j < n; ++j) {
    const Frame<double> f = rod.material_frame(j);
    s.d1.push_back(f.d1.values());
    s.d2.push_back(f.d2.values());
    s.stretching.push_back(stretch[j] / rod.rest_lengths()[j]);
  }
  s.curvature.assign(n + 1, 0.0);
  s.twist.assign(n + 1, 0.0);
  s.bending.assign(n + 1, 0.0);
  s.twisting.assign(n + 1, 0.0);
  for (int i = 1; i < n; ++i) {
    const double v = rod.voronoi_length(i);
    const VertexStrains<double> k = rod.strains(i);
    s.curvature[i] = norm(k.kb) / v;
    s.twist[i] = k.twist / v;
    s.bending[i] = bend[i] / v;
    s.twisting[i] = twist[i] / v;
  }
  return s;
}

template <class T>
void reverse_all(std::vector<T>& v) {
  std::reverse(v.begin(), v.end());
}

// A rod's section: that of its first segment (sections are set per full rod
// by the configuration's "rods").
SectionSnapshot rod_section(const RodLinkage& linkage, const RodChain& rod) {
  const Material& material =
      rod.segments.empty() ? linkage.options().material : linkage.segment_material(rod.segments[0]);
  SectionSnapshot section;
  section.shape = material.section.shape == SectionShape::Rectangle
                      ? SectionSnapshot::Shape::Rectangle
                      : SectionSnapshot::Shape::Ellipse;
  section.width = material.section.width;
  section.height = material.section.height;
  return section;
}

// Appends segment seg's sample s (in the rod's direction) to the rod.
// Consecutive segments share the terminal edge at their joint: it (and its
// two nodes) is skipped in the later one, whose vertex quantities at the
// node past the joint are kept.
void append_segment(const SegmentSample& s, int seg, const Eigen::Vector3d& origin,
                    RodSnapshot& out) {
  const size_t skip = out.nodes.empty() ? 0 : 2;
  if (skip) {
    out.curvature.back() = s.curvature[1];
    out.twist.back() = s.twist[1];
    out.bending_density.back() = s.bending[1];
    out.twisting_density.back() = s.twisting[1];
  }
  for (size_t i = skip; i < s.nodes.size(); ++i) {
    out.nodes.push_back(s.nodes[i] + origin);
    out.curvature.push_back(s.curvature[i]);
    out.twist.push_back(s.twist[i]);
    out.bending_density.push_back(s.bending[i]);
    out.twisting_density.push_back(s.twisting[i]);
  }
  for (size_t j = skip ? 1 : 0; j < s.d1.size(); ++j) {
    out.edge_segment.push_back(seg);
    out.d1.push_back(s.d1[j]);
    out.d2.push_back(s.d2[j]);
    out.stretching_density.push_back(s.stretching[j]);
  }
}

RodSnapshot rod_snapshot(const RodLinkage& linkage, int r, const Eigen::Vector3d& origin) {
  const RodChain& rod = linkage.topology().rods[r];
  RodSnapshot out;
  out.rod_id = r;
  out.section = rod_section(linkage, rod);
  for (size_t k = 0; k < rod.segments.size(); ++k) {
    const int seg = rod.segments[k];
    SegmentSample s = sample(linkage.segment(seg));
    if (!rod.forward[k]) {
      for (auto* v : {&s.nodes, &s.d1, &s.d2}) reverse_all(*v);
      for (auto* v : {&s.stretching, &s.curvature, &s.twist, &s.bending, &s.twisting})
        reverse_all(*v);
      // Twist (the rotation of d1 about t per length) is the same read in
      // either direction: both t and the arc length change sign.
    }
    append_segment(s, seg, origin, out);
  }
  return out;
}

}  // namespace

Snapshot linkage_snapshot(const RodLinkage& linkage, const Eigen::Vector3d& origin, double time) {
  Snapshot snap;
  snap.time = time;
  const int num_rods = static_cast<int>(linkage.topology().rods.size());
  for (int r = 0; r < num_rods; ++r) snap.rods.push_back(rod_snapshot(linkage, r, origin));
  const std::vector<int>& valence = linkage.topology().valence;
  for (int j = 0; j < linkage.num_joints(); ++j) {
    JointSnapshot js;
    js.vertex = linkage.topology().joints[j].vertex;
    js.position = linkage.joint(j).position() + origin;
    js.normal = linkage.joint(j).normal();
    js.opening_angle = linkage.joint(j).opening_angle();
    js.valence = valence[js.vertex];
    snap.joints.push_back(js);
  }
  validate(snap);
  return snap;
}

}  // namespace xshell
