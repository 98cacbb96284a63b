// From a configuration and its linkage graph to the model's inputs: the
// linkage options, the supports and loads, and the graph recentred at its
// bounding-box centre (the model works in recentred coordinates; outputs add
// the origin back).
#pragma once

#include "config.hpp"
#include "input_file.hpp"  // kMaxRodEdges
#include "linkage/statics_problem.hpp"

namespace xshell {

struct ProblemSetup {
  LineGraph graph;                                   // recentred
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // input bounding-box centre
  LinkageOptions options;
  StaticsSetup statics;  // forces, gravity, line loads and supports (one per resolved vertex)
  std::vector<std::vector<int>> support_vertices;  // per entry of config.supports, its vertices
};

// The graph is first transformed by config.transform, then the supports'
// selections resolved in it (resolve_supports). Throws InputError for vertex
// and rod indices out of range, for "rest_lengths" of another count than the
// graph's edges, for selections that select nothing, for a support that
// cannot apply (an opening angle held at a free rod end or at edge-vector
// joints), for more than kMaxRodEdges rod edges and for "rods" entries that
// do not apply (see segment_materials); ModelError when the graph is no
// linkage.
ProblemSetup make_problem_setup(const Config& config, const LineGraph& graph);

// The model's material of a configuration's material.
Material model_material(const MaterialConfig& material);

// Per segment (graph edge) of `topology`, its material: the top-level one,
// overridden by the entries of config.rods in order (the later wins where
// they select the same rod). Throws InputError naming the key for a rod
// index out of range or an edge [i, j] that is not in `graph`.
std::vector<Material> segment_materials(const Config& config, const LineGraph& graph,
                                        const LinkageTopology& topology);

}  // namespace xshell
