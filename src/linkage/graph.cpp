#include "graph.hpp"

#include <algorithm>

namespace xshell {

std::vector<int> valences(const LineGraph& graph) {
  std::vector<int> valence(graph.vertices.size(), 0);
  for (const auto& e : graph.edges) {
    ++valence[e[0]];
    ++valence[e[1]];
  }
  return valence;
}

std::vector<int> corner_vertices(const LineGraph& graph) {
  std::vector<int> corners;
  if (graph.vertices.empty()) return corners;
  for (const Eigen::Vector2d& d : {Eigen::Vector2d(1, 1), Eigen::Vector2d(1, -1),
                                   Eigen::Vector2d(-1, 1), Eigen::Vector2d(-1, -1)}) {
    int best = 0;
    for (int v = 1; v < static_cast<int>(graph.vertices.size()); ++v)
      if (d.dot(graph.vertices[v].head<2>()) > d.dot(graph.vertices[best].head<2>())) best = v;
    if (std::find(corners.begin(), corners.end(), best) == corners.end()) corners.push_back(best);
  }
  return corners;
}

}  // namespace xshell
