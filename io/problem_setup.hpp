// From a configuration and its linkage graph to the model's inputs: the
// linkage options, the supports and loads, and the graph recentred at its
// bounding-box centre (the model works in recentred coordinates; outputs add
// the origin back).
#pragma once

#include "config.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

struct ProblemSetup {
  LineGraph graph;                                  // recentred
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // input bounding-box centre
  LinkageOptions options;
  StaticsSetup statics;                             // forces, gravity and supports
};

// Throws InputError for vertex indices out of range.
ProblemSetup make_problem_setup(const Config& config, const LineGraph& graph);

}  // namespace xshell
