#include "support_selection.hpp"

#include <algorithm>

#include "config_parts.hpp"
#include "input_error.hpp"
#include "linkage/graph_boundary.hpp"
#include "linkage/model_error.hpp"

namespace xshell {

namespace {

std::string entry_key(std::size_t i) { return "supports[" + std::to_string(i) + "]"; }

std::vector<int> selected(const SupportSelect& s, const LineGraph& graph) {
  std::vector<int> out;
  const int n = static_cast<int>(graph.vertices.size());
  switch (s.kind) {
    case SelectKind::Boundary:
      return boundary_vertices(graph);
    case SelectKind::Valence: {
      const std::vector<int> valence = valences(graph);
      for (int v = 0; v < n; ++v)
        if (std::find(s.valences.begin(), s.valences.end(), valence[v]) != s.valences.end())
          out.push_back(v);
      break;
    }
    case SelectKind::Region:
      for (int v = 0; v < n; ++v) {
        const Eigen::Vector3d& x = graph.vertices[v];
        if ((x.array() >= s.region_min.array()).all() && (x.array() <= s.region_max.array()).all())
          out.push_back(v);
      }
      break;
    case SelectKind::Vertices:
      out = s.vertices;
      std::sort(out.begin(), out.end());
      break;
  }
  return out;
}

// Two entries, at least one of them a selector, that displace a common
// vertex differently (entries that both name a "vertex" are compared when
// the configuration is read).
void check_conflicts(const Config& config, const std::vector<std::vector<int>>& vertices) {
  const std::vector<Support>& supports = config.supports;
  for (std::size_t j = 0; j < supports.size(); ++j)
    for (std::size_t i = 0; i < j; ++i) {
      if (!supports[i].select && !supports[j].select) continue;
      const int c = conflicting_component(supports[i], supports[j]);
      if (c < 0) continue;
      for (int v : vertices[j])
        if (std::binary_search(vertices[i].begin(), vertices[i].end(), v))
          throw InputError(config.source + ": " + entry_key(j) + ": " +
                           support_conflict(v, entry_key(i), supports[i], supports[j], c));
    }
}

}  // namespace

std::vector<std::vector<int>> resolve_supports(const Config& config, const LineGraph& graph) {
  std::vector<std::vector<int>> out;
  for (std::size_t i = 0; i < config.supports.size(); ++i) {
    const Support& s = config.supports[i];
    if (!s.select) {
      out.push_back({s.vertex});
      continue;
    }
    const std::string key = config.source + ": " + entry_key(i) + ".select: ";
    try {
      out.push_back(selected(*s.select, graph));
    } catch (const ModelError& e) {
      throw InputError(key + e.what());
    }
    if (out.back().empty())
      throw InputError(key + "selects no vertex of the linkage (" +
                       std::to_string(graph.vertices.size()) + " vertices)");
  }
  check_conflicts(config, out);
  return out;
}

}  // namespace xshell
