#include "section_sweep.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace xshell {
namespace {

// d1 made orthogonal to the unit tangent t and normalized; `fallback` (also
// projected) when d1 is nearly parallel to t or zero.
Eigen::Vector3d orthogonal_unit(const Eigen::Vector3d& t, const Eigen::Vector3d& d1,
                                const Eigen::Vector3d& fallback) {
  for (const Eigen::Vector3d& candidate : {d1, fallback}) {
    const Eigen::Vector3d projected = candidate - candidate.dot(t) * t;
    if (projected.norm() > 1e-8) return projected.normalized();
  }
  // Any unit vector orthogonal to t.
  return t.unitOrthogonal();
}

}  // namespace

std::vector<Eigen::Vector2d> section_outline(const SectionSnapshot& section, int ellipse_sides) {
  if (!(section.width > 0.0) || !(section.height > 0.0))
    throw std::invalid_argument("section: width and height must be positive, got " +
                                std::to_string(section.width) + " x " +
                                std::to_string(section.height));
  const double a = 0.5 * section.width, b = 0.5 * section.height;
  if (section.shape == SectionSnapshot::Shape::Rectangle)
    return {{a, -b}, {a, b}, {-a, b}, {-a, -b}};
  if (ellipse_sides < 3)
    throw std::invalid_argument("section: an ellipse needs at least 3 sides, got " +
                                std::to_string(ellipse_sides));
  std::vector<Eigen::Vector2d> outline;
  outline.reserve(static_cast<size_t>(ellipse_sides));
  for (int j = 0; j < ellipse_sides; ++j) {
    const double theta = 2.0 * M_PI * j / ellipse_sides;
    outline.emplace_back(a * std::cos(theta), b * std::sin(theta));
  }
  return outline;
}

std::vector<NodeFrame> node_frames(const RodSnapshot& rod) {
  const size_t n_edges = rod.nodes.size() - 1;
  std::vector<Eigen::Vector3d> tangents(n_edges);
  std::vector<bool> defined(n_edges, false);
  for (size_t i = 0; i < n_edges; ++i) {
    // Scaled first: an edge of 1e-170 would square to zero. Only an edge of
    // exactly zero length (or a non-finite one) has no direction.
    const Eigen::Vector3d e = rod.nodes[i + 1] - rod.nodes[i];
    const double scale = e.cwiseAbs().maxCoeff();
    if (!(scale > 0.0) || !std::isfinite(scale)) continue;
    tangents[i] = (e / scale).normalized();
    defined[i] = true;
  }
  // An edge without a direction borrows one from the edges before it (the
  // leading ones from the first with a direction): a drawing must not fail,
  // the solver's states are checked elsewhere. A rod with no direction at
  // all is drawn normal to its first d1.
  const auto first = std::find(defined.begin(), defined.end(), true);
  Eigen::Vector3d carried = Eigen::Vector3d::UnitX();
  if (first != defined.end())
    carried = tangents[static_cast<size_t>(first - defined.begin())];
  else if (!rod.d1.empty() && rod.d1[0].allFinite() && rod.d1[0].norm() > 0.0)
    carried = rod.d1[0].unitOrthogonal();
  for (size_t i = 0; i < n_edges; ++i) {
    if (defined[i])
      carried = tangents[i];
    else
      tangents[i] = carried;
  }

  std::vector<NodeFrame> frames(n_edges + 1);
  for (size_t k = 0; k <= n_edges; ++k) {
    const size_t prev = (k == 0) ? 0 : k - 1;        // edge before the node
    const size_t next = (k == n_edges) ? k - 1 : k;  // edge after the node
    Eigen::Vector3d t = tangents[prev] + tangents[next];
    // A rod folding back on itself: no bisector, keep the next edge's tangent.
    t = (t.norm() > 1e-8) ? t.normalized() : tangents[next];
    NodeFrame& frame = frames[k];
    frame.tangent = t;
    frame.d1 = orthogonal_unit(t, rod.d1[prev] + rod.d1[next], rod.d1[next]);
    frame.d2 = t.cross(frame.d1);
  }
  return frames;
}

}  // namespace xshell
