// Target positions for chosen vertices of a linkage, and the least-squares
// fit to them (inverse design, docs/model.md section 9.7):
//   F(r) = 1/2 sum_v w_v |x_v(r) - t_v|^2,
// with x_v the vertex's position (RodLinkage::vertex_position): a joint's
// p, a free end's end node, or a clamped free end's end edge midpoint, each
// a linear function of the reduced unknowns r:
//   x_v = sum_k c_k (r_{i_k}, r_{i_k + 1}, r_{i_k + 2}).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "linkage/rod_linkage.hpp"

namespace xshell {

struct VertexTarget {
  int vertex = 0;                                      // graph vertex
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // t_v (length)
  double weight = 1.0;                                 // w_v (>= 0)
};

// The terms (i_k, c_k) of x_v above. Throws ModelError for a vertex out of
// range or a free end whose node is not an unknown of its own.
std::vector<std::pair<int, double>> vertex_position_terms(const RodLinkage& linkage, int vertex);

// F at the linkage's configuration (length^2).
double target_fit(const RodLinkage& linkage, const std::vector<VertexTarget>& targets);
// dF/dr over all reduced unknowns (num_dofs()).
Eigen::VectorXd target_fit_gradient(const RodLinkage& linkage,
                                    const std::vector<VertexTarget>& targets);

}  // namespace xshell
