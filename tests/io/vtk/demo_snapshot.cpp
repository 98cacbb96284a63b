#include "demo_snapshot.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace xshell::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Fills the per-edge frames (twisted by `twist_rate` rad per edge around a
// frame built from `reference`) and every density of a rod whose nodes and
// segments are already set.
void fill_rod(RodSnapshot& rod, const Eigen::Vector3d& reference, double twist_rate) {
  const size_t n = rod.nodes.size() - 1;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d t = (rod.nodes[i + 1] - rod.nodes[i]).normalized();
    const Eigen::Vector3d b1 = (reference - reference.dot(t) * t).normalized();
    const Eigen::Vector3d b2 = t.cross(b1);
    const double phi = twist_rate * static_cast<double>(i);
    const Eigen::Vector3d d1 = std::cos(phi) * b1 + std::sin(phi) * b2;
    rod.d1.push_back(d1);
    rod.d2.push_back(t.cross(d1));
    rod.stretching_density.push_back(1e-3 * (1.0 + static_cast<double>(i)));
  }
  for (size_t k = 0; k <= n; ++k) {
    const bool end = (k == 0 || k == n);
    const double s = static_cast<double>(k) / static_cast<double>(n);
    rod.curvature.push_back(end ? 0.0 : 2.0 + std::sin(kPi * s));
    rod.twist.push_back(end ? 0.0 : twist_rate * (1.0 + s));
    rod.bending_density.push_back(end ? 0.0 : 0.5 * std::sin(kPi * s) * (1.0 + s));
    rod.twisting_density.push_back(end ? 0.0 : 0.1 * s);
  }
}

JointSnapshot joint(int vertex, const Eigen::Vector3d& position, const Eigen::Vector3d& normal,
                    double opening_angle, int valence) {
  JointSnapshot j;
  j.vertex = vertex;
  j.position = position;
  j.normal = normal.normalized();
  j.opening_angle = opening_angle;
  j.valence = valence;
  return j;
}

}  // namespace

Snapshot demo_snapshot(double time, double phase) {
  const double bulge = 0.1 * (1.0 + 0.2 * std::sin(phase));
  Snapshot snapshot;
  snapshot.time = time;

  RodSnapshot a;
  a.rod_id = 7;
  a.section = {SectionSnapshot::Shape::Rectangle, 0.02, 0.005};
  for (int k = 0; k <= 8; ++k) {
    const double x = k / 8.0;
    a.nodes.emplace_back(x, 0.0, bulge * std::sin(kPi * x));
    if (k < 8) a.edge_segment.push_back(k < 4 ? 0 : 1);
  }
  fill_rod(a, Eigen::Vector3d(0.1, 1.0, 0.2), 0.15);

  RodSnapshot b;
  b.rod_id = 9;
  b.section = {SectionSnapshot::Shape::Ellipse, 0.015, 0.008};
  for (int k = 0; k <= 6; ++k) {
    const double y = -0.5 + k / 6.0;
    b.nodes.emplace_back(0.5, y, bulge * std::cos(kPi * y));
    if (k < 6) b.edge_segment.push_back(k < 3 ? 2 : 3);
  }
  fill_rod(b, Eigen::Vector3d(1.0, -0.2, 0.3), -0.2);

  const Eigen::Vector3d crossing = a.nodes[4];  // = b.nodes[3]
  snapshot.joints = {
      joint(0, a.nodes.front(), a.d2.front(), 0.5 * kPi, 1),
      joint(1, crossing, Eigen::Vector3d(0.1, -0.2, 1.0), 0.5 * kPi - 0.1, 4),
      joint(2, a.nodes.back(), a.d2.back(), 0.5 * kPi, 1),
      joint(3, b.nodes.front(), b.d2.front(), 0.5 * kPi, 1),
      joint(4, b.nodes.back(), b.d2.back(), 0.5 * kPi, 1),
  };
  snapshot.rods = {a, b};
  return snapshot;
}

Snapshot straight_rod_snapshot(const SectionSnapshot& section, const Eigen::Vector3d& start,
                               const Eigen::Vector3d& end, int n_edges) {
  RodSnapshot rod;
  rod.rod_id = 0;
  rod.section = section;
  for (int k = 0; k <= n_edges; ++k) {
    rod.nodes.push_back(start + (end - start) * (static_cast<double>(k) / n_edges));
    if (k < n_edges) rod.edge_segment.push_back(0);
  }
  fill_rod(rod, Eigen::Vector3d(0.3, -0.7, 0.5), 0.0);

  Snapshot snapshot;
  snapshot.rods = {rod};
  snapshot.joints = {joint(0, start, rod.d2.front(), 1.0, 1), joint(1, end, rod.d2.back(), 1.0, 1)};
  return snapshot;
}

Snapshot grid_snapshot(int n, double height) {
  const int edges = 4 * (n - 1);
  auto at = [&](double x, double y) {
    return Eigen::Vector3d(x, y, height * (1.0 - 4.0 * (x * x + y * y)));
  };
  const auto coordinate = [&](int i) { return -0.5 + static_cast<double>(i) / (n - 1); };
  Snapshot snapshot;
  for (int along_y = 0; along_y < 2; ++along_y)
    for (int i = 0; i < n; ++i) {
      RodSnapshot rod;
      rod.rod_id = along_y * n + i;
      rod.section = {SectionSnapshot::Shape::Rectangle, 0.01, 0.01};
      for (int k = 0; k <= edges; ++k) {
        const double s = -0.5 + static_cast<double>(k) / edges;
        rod.nodes.push_back(along_y ? at(coordinate(i), s) : at(s, coordinate(i)));
        if (k < edges) rod.edge_segment.push_back(rod.rod_id * (n - 1) + k / 4);
      }
      fill_rod(rod, Eigen::Vector3d(0.0, 0.0, 1.0), 0.0);
      snapshot.rods.push_back(rod);
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      snapshot.joints.push_back(joint(i * n + j, at(coordinate(i), coordinate(j)),
                                      Eigen::Vector3d::UnitZ(), 0.5 * kPi, 4));
  return snapshot;
}

}  // namespace xshell::test
