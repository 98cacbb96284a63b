#include "integrators/design/vertex_targets.hpp"

#include <string>

#include "linkage/model_error.hpp"

namespace xshell {

namespace {

int node_unknown(const RodLinkage& linkage, int segment, int node, int vertex) {
  const int index = linkage.reduced_index(segment, ElasticRod::node_dof(node));
  if (index < 0)
    throw ModelError("vertex " + std::to_string(vertex) +
                     ": its end node is not an unknown of its segment");
  return index;
}

}  // namespace

std::vector<std::pair<int, double>> vertex_position_terms(const RodLinkage& linkage, int vertex) {
  if (vertex < 0 || vertex >= static_cast<int>(linkage.graph().vertices.size()))
    throw ModelError("target vertex " + std::to_string(vertex) + " is not a vertex of the linkage");
  const int j = linkage.topology().joint_of_vertex[vertex];
  if (j >= 0) return {{linkage.joint_dof_offset(j) + kPosition, 1.0}};
  const RodLinkage::FreeEnd f = linkage.free_end(vertex);
  const int end = node_unknown(linkage, f.segment, f.end_node, vertex);
  if (!f.clamped) return {{end, 1.0}};
  return {{end, 0.5}, {node_unknown(linkage, f.segment, f.next_node, vertex), 0.5}};
}

double target_fit(const RodLinkage& linkage, const std::vector<VertexTarget>& targets) {
  double fit = 0.0;
  for (const VertexTarget& t : targets)
    fit += 0.5 * t.weight * (linkage.vertex_position(t.vertex) - t.position).squaredNorm();
  return fit;
}

Eigen::VectorXd target_fit_gradient(const RodLinkage& linkage,
                                    const std::vector<VertexTarget>& targets) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(linkage.num_dofs());
  for (const VertexTarget& t : targets) {
    const Eigen::Vector3d d = t.weight * (linkage.vertex_position(t.vertex) - t.position);
    for (const auto& [index, c] : vertex_position_terms(linkage, t.vertex))
      g.segment<3>(index) += c * d;
  }
  return g;
}

}  // namespace xshell
