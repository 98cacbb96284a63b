// The user's choice of branch as a vector over the free unknowns: which
// way a symmetric (e.g. flat) linkage leaves its symmetric state
// ("solver.buckling_direction", default +z).
//
// For a displacement dq of the free unknowns, bias . dq is the mean
// displacement along the unit direction b of the linkage's vertices (as the
// summary's `vertices`: a joint's position, a free end's end node, a clamped
// end's end-edge midpoint; zero where held), to first order. The saddle
// escape (saddle_escape.hpp) signs its mode so that this is positive.
// Edge-vector joints have their position first too, so the rule is the
// same for them.
#pragma once

#include <Eigen/Core>

#include "linkage/statics_problem.hpp"

namespace xshell {

// bias (problem.num_free()) for direction b (any length, not zero).
Eigen::VectorXd branch_bias(const LinkageProblem& problem, const Eigen::Vector3d& direction);

// The vertices' mean displacement from the input (the graph's vertices)
// along the unit direction b: the side of the branch rule the state is on.
double mean_displacement(const LinkageProblem& problem, const Eigen::Vector3d& direction);

}  // namespace xshell
