#include "problem_setup.hpp"

#include "input_error.hpp"
#include "linkage/bounding_box.hpp"
#include "support_selection.hpp"

namespace xshell {

namespace {
SupportDof to_support(Fixed f) {
  switch (f) {
    case Fixed::Position:
      return SupportDof::Position;
    case Fixed::X:
      return SupportDof::X;
    case Fixed::Y:
      return SupportDof::Y;
    case Fixed::Z:
      return SupportDof::Z;
    case Fixed::Orientation:
      return SupportDof::Orientation;
    case Fixed::OpeningAngle:
      return SupportDof::OpeningAngle;
  }
  return SupportDof::Position;
}
// Supports that cannot apply to their vertex, named by their key (the model
// would refuse them too, but in words about the linkage, not the
// configuration): an opening angle fixed at a free rod end, or at an
// edge-vector joint (which has no opening-angle unknown).
void check_support_kinds(const Config& config, const LineGraph& graph,
                         const std::vector<std::vector<int>>& vertices) {
  const std::vector<int> valence = valences(graph);
  for (std::size_t i = 0; i < config.supports.size(); ++i) {
    const Support& s = config.supports[i];
    for (std::size_t k = 0; k < s.fix.size(); ++k) {
      if (s.fix[k] != Fixed::OpeningAngle) continue;
      const std::string key = config.source + ": supports[" + std::to_string(i) + "].fix[" +
                              std::to_string(k) + "]: \"opening_angle\": ";
      for (int v : vertices[i])
        if (valence[v] == 1)
          throw InputError(key + "vertex " + std::to_string(v) +
                           " is a free rod end, which has no opening angle to fix");
      if (config.joints == JointModel::EdgeVectors)
        throw InputError(key +
                         "edge-vector joints (\"joints\": \"edge_vectors\") have no "
                         "opening-angle unknown; fix \"orientation\" (both rod directions, "
                         "hence the angle too) or use \"joints\": \"rotation\"");
    }
  }
}
// Rod indices of "loads.line_loads" beyond the linkage's rods.
void check_line_loads(const Config& config, const LineGraph& graph) {
  int num_rods = -1;
  for (std::size_t i = 0; i < config.loads.line_loads.size(); ++i) {
    const std::vector<int>& rods = config.loads.line_loads[i].rods;
    if (rods.empty()) continue;
    if (num_rods < 0) num_rods = static_cast<int>(build_topology(graph).rods.size());
    for (std::size_t k = 0; k < rods.size(); ++k)
      if (rods[k] >= num_rods)
        throw InputError(config.source + ": loads.line_loads[" + std::to_string(i) + "].rods[" +
                         std::to_string(k) + "]: rod " + std::to_string(rods[k]) +
                         " is out of range; the linkage has " + std::to_string(num_rods) +
                         " rods (0-based, numbered as the rod_id cell data of the output's "
                         "rods_*.vtp)");
  }
}
// "rest_lengths": one per segment (edge of the linkage file).
void check_rest_lengths(const Config& config, const LineGraph& graph) {
  const std::size_t given = config.rest_lengths.size(), segments = graph.edges.size();
  if (given == 0 || given == segments) return;
  const std::string count = std::to_string(segments);
  throw InputError(config.source + ": rest_lengths: " + std::to_string(given) +
                   (given == 1 ? " rest length" : " rest lengths") + " given; the linkage has " +
                   count + (segments == 1 ? " segment" : " segments") + ", so it needs " + count +
                   " (one per edge, in the order of the linkage file's 'l' lines: 'l a b c' "
                   "gives the edges a-b, b-c)");
}
}  // namespace

Material model_material(const MaterialConfig& m) {
  Material out;
  out.young_modulus = m.young_modulus;
  out.poisson_ratio = m.poisson_ratio;
  out.density = m.density;
  out.strength = m.strength.value_or(0.0);
  out.section = {m.cross_section.shape, m.cross_section.width, m.cross_section.height};
  return out;
}

std::vector<Material> segment_materials(const Config& config, const LineGraph& graph,
                                        const LinkageTopology& topology) {
  const int num_rods = static_cast<int>(topology.rods.size());
  std::vector<Material> rod_material(num_rods, model_material(config.material));
  for (std::size_t i = 0; i < config.rods.size(); ++i) {
    const RodMaterial& entry = config.rods[i];
    const std::string key = config.source + ": rods[" + std::to_string(i) + "]";
    std::vector<int> selected;
    switch (entry.selector) {
      case RodSelector::Rod:
        if (entry.rod >= num_rods)
          throw InputError(key + ".rod: rod " + std::to_string(entry.rod) +
                           " is out of range; the linkage has " + std::to_string(num_rods) +
                           " rods (0-based indices 0 to " + std::to_string(num_rods - 1) +
                           ", numbered as the rod_id cell data of the output's rods_*.vtp)");
        selected.push_back(entry.rod);
        break;
      case RodSelector::Edges:
        for (std::size_t k = 0; k < entry.edges.size(); ++k) {
          const auto [a, b] = entry.edges[k];
          int found = -1;
          for (std::size_t e = 0; e < graph.edges.size() && found < 0; ++e)
            if ((graph.edges[e][0] == a && graph.edges[e][1] == b) ||
                (graph.edges[e][0] == b && graph.edges[e][1] == a))
              found = static_cast<int>(e);
          if (found < 0)
            throw InputError(key + ".edges[" + std::to_string(k) + "]: vertices " +
                             std::to_string(a) + " and " + std::to_string(b) +
                             " are not joined by an edge of the linkage");
          selected.push_back(topology.segments[found].rod);
        }
        break;
      case RodSelector::Vertices:
        for (int v : entry.vertices)
          for (const SegmentTopology& seg : topology.segments)
            if (seg.vertex[0] == v || seg.vertex[1] == v) selected.push_back(seg.rod);
        break;
    }
    for (int rod : selected) rod_material[rod] = model_material(entry.material);
  }
  std::vector<Material> out;
  for (const SegmentTopology& seg : topology.segments) out.push_back(rod_material[seg.rod]);
  return out;
}

ProblemSetup make_problem_setup(const Config& config, const LineGraph& input) {
  const LineGraph graph = transformed(input, config.transform);
  check_vertices(config, graph);
  const std::vector<std::vector<int>> support_vertices = resolve_supports(config, graph);
  check_support_kinds(config, graph, support_vertices);
  check_rest_lengths(config, graph);
  // A linkage far beyond any machine's memory is refused here, with the key
  // to change, rather than failing in an allocation (or the kernel's OOM killer).
  const double rod_edges = static_cast<double>(graph.edges.size()) * config.subdivisions;
  if (rod_edges > kMaxRodEdges)
    throw InputError(config.source + ": subdivisions: " + std::to_string(config.subdivisions) +
                     " x " + std::to_string(graph.edges.size()) + " segments makes " +
                     std::to_string(static_cast<long long>(rod_edges)) + " rod edges; at most " +
                     std::to_string(kMaxRodEdges) + " are supported");
  ProblemSetup setup;
  setup.support_vertices = support_vertices;
  setup.origin = bounding_box(graph.vertices).centre();
  setup.graph = graph;
  for (auto& v : setup.graph.vertices) v -= setup.origin;

  setup.options.subdivisions = config.subdivisions;
  setup.options.rest_shape = config.rest_shape;
  setup.options.segment_rest_lengths = config.rest_lengths;
  setup.options.joint_kind =
      config.joints == JointModel::EdgeVectors ? JointKind::EdgeVectors : JointKind::Rotation;
  setup.options.material = model_material(config.material);
  if (!config.rods.empty())
    setup.options.segment_materials =
        segment_materials(config, setup.graph, build_topology(setup.graph));

  for (std::size_t i = 0; i < config.supports.size(); ++i) {
    const Support& s = config.supports[i];
    for (int v : support_vertices[i]) {
      VertexSupport vs{v, {}, s.displacement};
      for (Fixed f : s.fix) vs.fix.push_back(to_support(f));
      setup.statics.supports.push_back(vs);
    }
  }
  // A clamped free end's end edge is centred on its vertex when the linkage
  // is built (docs/model.md section 8.2).
  setup.options.clamped_ends = clamped_free_ends(setup.graph, setup.statics.supports);
  setup.statics.gravity = config.loads.gravity;
  for (const PointForce& f : config.loads.forces)
    setup.statics.forces.push_back({f.vertex, f.force});
  check_line_loads(config, setup.graph);
  for (const LineLoadConfig& l : config.loads.line_loads)
    setup.statics.line_loads.push_back({l.rods, l.force_per_length});
  return setup;
}

}  // namespace xshell
