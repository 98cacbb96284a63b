#include "integrators/stability/branch_bias.hpp"

#include <algorithm>

namespace xshell {

namespace {

// Adds weight * b to the free entries of the reduced unknowns r..r+2.
void add_point(const std::vector<int>& free, int r, const Eigen::Vector3d& b,
               Eigen::VectorXd& bias) {
  for (int k = 0; k < 3; ++k) {
    const auto it = std::lower_bound(free.begin(), free.end(), r + k);
    if (it != free.end() && *it == r + k) bias[it - free.begin()] += b[k];
  }
}

}  // namespace

Eigen::VectorXd branch_bias(const LinkageProblem& problem, const Eigen::Vector3d& direction) {
  const RodLinkage& linkage = problem.linkage();
  const std::vector<int>& free = problem.free_indices();
  Eigen::VectorXd bias = Eigen::VectorXd::Zero(problem.num_free());
  const int vertices = static_cast<int>(linkage.graph().vertices.size());
  if (vertices == 0) return bias;
  const Eigen::Vector3d b = direction.normalized() / vertices;
  for (int v = 0; v < vertices; ++v) {
    const int j = linkage.topology().joint_of_vertex[v];
    if (j >= 0) {
      add_point(free, linkage.joint_dof_offset(j), b, bias);  // the position comes first
      continue;
    }
    const RodLinkage::FreeEnd end = linkage.free_end(v);
    if (end.segment < 0) continue;
    const int r = linkage.reduced_index(end.segment, ElasticRod::node_dof(end.end_node));
    if (!end.clamped) {
      if (r >= 0) add_point(free, r, b, bias);
      continue;
    }
    // A clamped end's vertex is the midpoint of its end edge.
    const int r_next = linkage.reduced_index(end.segment, ElasticRod::node_dof(end.next_node));
    if (r >= 0) add_point(free, r, 0.5 * b, bias);
    if (r_next >= 0) add_point(free, r_next, 0.5 * b, bias);
  }
  return bias;
}

double mean_displacement(const LinkageProblem& problem, const Eigen::Vector3d& direction) {
  const std::vector<Eigen::Vector3d> now = problem.vertex_positions();
  const std::vector<Eigen::Vector3d>& input = problem.linkage().graph().vertices;
  if (now.empty()) return 0.0;
  const Eigen::Vector3d b = direction.normalized();
  double sum = 0.0;
  for (size_t v = 0; v < now.size(); ++v) sum += (now[v] - input[v]).dot(b);
  return sum / static_cast<double>(now.size());
}

}  // namespace xshell
