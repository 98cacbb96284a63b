// Internal forces and stresses in every rod edge of a linkage, with the
// section of its own segment (rod/rod_forces.hpp, rod/section_stress.hpp).
//
// The terminal edge at a joint belongs to both segments that meet there;
// each reports it with its own moments (those of its interior vertex next
// to the joint). Utilisation, where the segment's material has a strength
// S > 0: the equivalent stress sqrt(sigma_max^2 + 3 tau^2) over S, with
// sigma_max the largest combined normal stress and tau the torsional shear
// (von Mises; conservative, as the two peaks need not meet at one point).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "rod/rod_forces.hpp"
#include "rod_linkage.hpp"

namespace xshell {

struct EdgeStress {
  SectionForces forces;
  SectionStresses stresses;
  double equivalent = 0.0;            // sqrt(sigma_max^2 + 3 tau^2)
  std::optional<double> utilisation;  // equivalent / strength
};

// Where a maximum occurs.
struct EdgeLocation {
  double value = 0.0;
  int segment = -1, edge = -1;
  int rod = -1;                                        // the full rod of the segment (topology.hpp)
  Eigen::Vector3d midpoint = Eigen::Vector3d::Zero();  // model coordinates
};

struct LinkageStresses {
  std::vector<std::vector<EdgeStress>> segments;                         // [segment][edge]
  EdgeLocation max_normal_stress, max_torsional_shear, max_axial_force;  // |N| for the last
  std::optional<EdgeLocation> max_utilisation;  // when some segment has a strength
};

LinkageStresses linkage_stresses(const RodLinkage& linkage);

}  // namespace xshell
