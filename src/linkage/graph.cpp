#include "graph.hpp"

namespace xshell {

std::vector<int> valences(const LineGraph& graph) {
  std::vector<int> valence(graph.vertices.size(), 0);
  for (const auto& e : graph.edges) {
    ++valence[e[0]];
    ++valence[e[1]];
  }
  return valence;
}

}  // namespace xshell
