// A plain snapshot of a linkage's geometry at one output step: what the VTK
// writers draw. The model fills it (io/linkage_snapshot); the writers know
// nothing else of the model.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace xshell {

struct SectionSnapshot {
  enum class Shape { Rectangle, Ellipse };
  Shape shape = Shape::Rectangle;
  double width = 0.0;   // along d1 (length unit)
  double height = 0.0;  // along d2 (length unit)
};

// One full rod: a polyline through its segments and joints.
struct RodSnapshot {
  int rod_id = 0;
  SectionSnapshot section;
  std::vector<Eigen::Vector3d> nodes;  // n + 1 points, in order along the rod

  // Per edge (n entries; edge i joins nodes i and i + 1).
  std::vector<int> edge_segment;           // graph edge (segment) index, 0-based
  std::vector<Eigen::Vector3d> d1, d2;     // material frame, unit, orthogonal to the edge
  std::vector<double> stretching_density;  // stretching energy per unit length

  // Per node (n + 1 entries; 0 at the two ends).
  std::vector<double> curvature;         // |curvature binormal| / Voronoi length (1/length)
  std::vector<double> twist;             // material twist / Voronoi length (rad/length)
  std::vector<double> bending_density;   // bending energy per unit length
  std::vector<double> twisting_density;  // twisting energy per unit length
};

struct JointSnapshot {
  int vertex = 0;  // graph vertex index, 0-based
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit; equals d2 of its terminal edges
  double opening_angle = 0.0;                         // radians, in (0, pi)
  int valence = 0;
  // Force the pin applies to rod A and to rod B (joint_forces.hpp), when
  // computed (final state); written only when every joint has them.
  std::optional<Eigen::Vector3d> pin_force_a, pin_force_b;
  // Distance to the inverse design's target (length unit), when the joint
  // has one; written when any joint has it (NaN for the others).
  std::optional<double> target_distance;
};

struct Snapshot {
  double time = 0.0;  // simulated time, or iteration/step index
  std::vector<RodSnapshot> rods;
  std::vector<JointSnapshot> joints;
};

// Throws std::invalid_argument when array sizes disagree with the rods'
// node counts.
void validate(const Snapshot& snapshot);

}  // namespace xshell
