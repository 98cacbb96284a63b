// The engineering results of a run in summary.json: support reactions,
// rod stresses, joint (pin) forces and the stability analysis. Each key of
// engineering_json() goes to the top level of summary.json
// (RunSummary::engineering). Positions are in input coordinates (the
// model's recentred ones plus `origin`).
//
//   reactions        per supported vertex: {vertex, position [x, y, z], force [fx, fy, fz]
//                    (force unit, on the linkage), moment [mx, my, mz] about position (force x
//                    length) or null where no orientation is fixed, opening_torque (force x
//                    length) or null where the opening angle is free}
//   stresses         {max_normal_stress, max_torsional_shear, max_axial_force (|N|),
//                    max_utilisation (null without material strength)}, each {value, rod,
//                    segment, edge, position (edge midpoint)}; stresses in force / length^2,
//                    utilisation dimensionless
//   joint_forces     per joint: {vertex, rods [A, B], force_on_a, force_on_b (force unit: the
//                    force the pin applies to each rod), moment_on_a, moment_on_b (force x
//                    length, about the joint; null for edge-vector joints)}
//   lowest_eigenvalues, buckling_load_factor, stability_analysis: see StabilityValues
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "linkage/joint_forces.hpp"
#include "linkage/reactions.hpp"
#include "linkage/rod_stresses.hpp"

namespace xshell {

// The stability analysis, as plain values (integrators/stability_analysis.hpp
// computes them).
struct StabilityValues {
  std::vector<double> lowest_eigenvalues;      // of H phi = lambda M phi, ascending; 1/time^2
  std::optional<double> buckling_load_factor;  // null when there is none
  std::string buckling_status;  // "found" | "no_buckling" | "unloaded_unstable" | ...
  std::string eigen_status;     // "converged" or why not
};

struct EngineeringResults {
  std::vector<SupportReaction> reactions;
  LinkageStresses stresses;
  std::vector<JointForce> joint_forces;
  std::optional<StabilityValues> stability;
};

nlohmann::json engineering_json(const EngineeringResults& results, const Eigen::Vector3d& origin);

}  // namespace xshell
