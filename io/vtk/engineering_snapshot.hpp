// Plain data for the VTK files of the engineering results of a final state
// (support reactions, per-edge stresses, joint forces, vibration and
// buckling modes); engineering_snapshot() fills them from the model, the
// writers (engineering_files.hpp) know nothing else of it. Positions are in
// input coordinates.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "io/engineering_json.hpp"
#include "linkage/rod_linkage.hpp"
#include "snapshot.hpp"

namespace xshell {

struct ReactionGlyph {
  int vertex = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // force unit
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // force x length; 0 where orientation is free
};

// One rod edge and what it carries.
struct EdgeResult {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  // end nodes
  int rod_id = 0, segment_id = 0;
  double axial_force = 0, bending_moment1 = 0, bending_moment2 = 0, torque = 0;
  double axial_stress = 0, bending_stress1 = 0, bending_stress2 = 0, torsional_shear = 0;
  double max_normal_stress = 0, equivalent_stress = 0;
  double utilisation = -1.0;  // -1 without a strength
};

// A displacement field on every rod node (one polyline per segment).
struct ModeField {
  std::string name;                                        // point-data array name, e.g. "mode_0"
  std::vector<std::vector<Eigen::Vector3d>> displacement;  // [segment][node]
};

struct EngineeringSnapshot {
  std::vector<ReactionGlyph> reactions;
  std::vector<EdgeResult> edges;
  Snapshot joints;                                          // joints only, with pin forces
  std::vector<std::vector<Eigen::Vector3d>> segment_nodes;  // [segment][node], for the modes
  std::vector<ModeField> modes;
};

EngineeringSnapshot engineering_snapshot(const RodLinkage& linkage,
                                         const EngineeringResults& results,
                                         const Eigen::Vector3d& origin);

}  // namespace xshell
