#include "graph_boundary.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "model_error.hpp"

namespace xshell {

namespace {

using Point = Eigen::Vector2d;

double cross(const Point& a, const Point& b) { return a.x() * b.y() - a.y() * b.x(); }

// The vertices in the best-fit plane's coordinates: along the directions of
// the two largest spreads, from the centroid.
std::vector<Point> projected(const LineGraph& graph) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : graph.vertices) centroid += v;
  centroid /= static_cast<double>(graph.vertices.size());
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& v : graph.vertices)
    spread += (v - centroid) * (v - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(spread);  // ascending
  const Eigen::Vector3d u = eigen.eigenvectors().col(2), w = eigen.eigenvectors().col(1);
  std::vector<Point> points;
  for (const Eigen::Vector3d& v : graph.vertices)
    points.emplace_back((v - centroid).dot(u), (v - centroid).dot(w));
  return points;
}

// Throws when two edges without a common vertex cross in the plane. Points
// within round-off of an edge's line count as on it (collinear edges, as
// along a straight lath, do not cross).
void check_no_crossings(const LineGraph& graph, const std::vector<Point>& p) {
  double size = 0.0;
  for (const Point& x : p) size = std::max(size, x.norm());
  const double round_off = 1e-12 * size * size;
  const auto side = [&](int a, int b, int c) {
    const double s = cross(p[b] - p[a], p[c] - p[a]);
    return std::abs(s) <= round_off ? 0.0 : s;
  };
  for (std::size_t i = 0; i < graph.edges.size(); ++i)
    for (std::size_t j = i + 1; j < graph.edges.size(); ++j) {
      const auto [a, b] = graph.edges[i];
      const auto [c, d] = graph.edges[j];
      if (a == c || a == d || b == c || b == d) continue;
      if (side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0)
        throw ModelError("the boundary is not defined: projected onto its best-fit plane, the " +
                         std::string("linkage's edges ") + std::to_string(a) + "-" +
                         std::to_string(b) + " and " + std::to_string(c) + "-" + std::to_string(d) +
                         " cross (select the rim by valence or region)");
    }
}

// The neighbour of v reached first turning counter-clockwise from the
// direction back to `from` (back to `from` itself only at a dead end).
int next_around(int v, int from, const std::vector<std::vector<int>>& neighbours,
                const std::vector<Point>& p) {
  const Point back = p[from] - p[v];
  int best = from;
  double best_angle = 2.0 * M_PI;
  for (int w : neighbours[v]) {
    if (w == from)
      continue;  // not by its angle: round-off (a fused multiply-add) may make it
                 // tiny instead of 2 pi
    const Point d = p[w] - p[v];
    double angle = std::atan2(cross(back, d), back.dot(d));
    if (angle <= 0.0) angle += 2.0 * M_PI;
    if (angle < best_angle) {
      best_angle = angle;
      best = w;
    }
  }
  return best;
}

// The vertices met walking around the outside of the drawing: from the
// leftmost vertex, as if arriving from further left, always taking the
// next edge counter-clockwise, so that the outer face stays on the right.
std::vector<int> outer_walk(const LineGraph& graph, const std::vector<Point>& p) {
  std::vector<std::vector<int>> neighbours(graph.vertices.size());
  for (const auto& [a, b] : graph.edges) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  int start = -1;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (!neighbours[v].empty() && (start < 0 || p[v].x() < p[start].x() ||
                                   (p[v].x() == p[start].x() && p[v].y() < p[start].y())))
      start = static_cast<int>(v);
  // A virtual vertex to the left of the start: the direction we came from.
  std::vector<Point> q = p;
  q.push_back(p[start] - Point(1.0, 0.0));
  const int first = next_around(start, static_cast<int>(p.size()), neighbours, q);
  std::vector<int> rim = {start};
  int from = start, at = first;
  for (std::size_t steps = 0; !(from == start && at == first && steps > 0); ++steps) {
    if (steps > 2 * graph.edges.size())
      throw ModelError("the boundary is not defined: the walk around the linkage's outside " +
                       std::string("does not close"));
    rim.push_back(at);
    const int next = next_around(at, from, neighbours, p);
    from = at;
    at = next;
  }
  return rim;
}

}  // namespace

std::vector<int> boundary_vertices(const LineGraph& graph) {
  if (graph.edges.empty()) throw ModelError("the boundary is not defined: the graph has no edge");
  const std::vector<Point> p = projected(graph);
  check_no_crossings(graph, p);
  std::vector<int> rim = outer_walk(graph, p);
  const std::vector<int> valence = valences(graph);
  for (std::size_t v = 0; v < valence.size(); ++v)
    if (valence[v] == 1) rim.push_back(static_cast<int>(v));
  std::sort(rim.begin(), rim.end());
  rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
  return rim;
}

}  // namespace xshell
