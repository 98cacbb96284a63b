// The range of a linkage's opening angles, and the joints whose angle has
// left (0, pi).
//
// A scissor joint's opening angle alpha (docs/model.md, the joint's bisector
// frame: the angle from t_A to t_B about the normal) lies in (0, pi) for a
// linkage that can be built: at alpha = 0 or pi the two rods are parallel,
// and beyond they have passed through each other at the joint, which the
// pin of a real linkage does not allow. The model has no barrier there (a
// rotation joint's alpha is an unknown like any other), so a solve can end
// beyond it; this check says where. Edge-vector joints measure an unsigned
// angle in [0, pi] (atan2 of |e_A x e_B| and e_A . e_B): only a joint exactly
// at 0 or pi shows there.
#pragma once

#include <optional>
#include <vector>

#include "rod_linkage.hpp"

namespace xshell {

// A joint whose opening angle is outside (0, pi).
struct JointOutsideOpeningRange {
  int vertex = 0;      // graph (OBJ) vertex, 0-based
  double angle = 0.0;  // radians
};

struct OpeningAngleRange {
  std::optional<double> min, max;                 // over every joint, radians; none without joints
  std::optional<int> min_vertex, max_vertex;      // where they are (graph vertices)
  std::vector<JointOutsideOpeningRange> outside;  // angle <= 0 or >= pi, by vertex
};

// The opening angles of `linkage`'s joints in its current state.
OpeningAngleRange opening_angle_range(const RodLinkage& linkage);

// The same for opening angles per graph vertex (nullopt at free ends), as
// LinkageProblem::opening_angles() gives them.
OpeningAngleRange opening_angle_range(const std::vector<std::optional<double>>& angles);

}  // namespace xshell
