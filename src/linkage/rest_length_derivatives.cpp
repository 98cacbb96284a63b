// Derivatives of the linkage energy and gradient with respect to the
// segment rest lengths p (docs/model.md section 9.7). Segment s's edge
// rest lengths are l_j = p_s r_j with r_j fixed (section 3.8), so
// d/dp_s = (1/p_s) d/dlambda of a uniform scale of its rod's rest lengths
// (rod/rest_scale_derivatives.hpp), and the mixed derivative follows the
// gradient's chain rule through the joints, J_s^T d(dE_s/dv)/dp_s: the
// joint maps (J_s, LocalMap) do not depend on the rest lengths.
#include "rod/rest_scale_derivatives.hpp"
#include "rod_linkage.hpp"

namespace xshell {

Eigen::VectorXd RodLinkage::energy_rest_length_derivative() const {
  const std::vector<double> p = segment_rest_lengths();
  Eigen::VectorXd d(num_segments());
  for (int s = 0; s < num_segments(); ++s) d[s] = rest_scale_energy_derivative(rods_[s]) / p[s];
  return d;
}

Eigen::SparseMatrix<double> RodLinkage::gradient_rest_length_derivative() const {
  const std::vector<double> p = segment_rest_lengths();
  std::vector<Eigen::Triplet<double>> triplets;
  for (int s = 0; s < num_segments(); ++s) {
    const Eigen::VectorXd dv = rest_scale_gradient_derivative(rods_[s]) / p[s];
    const LocalMap map = local_map(s, false);
    const Eigen::VectorXd local = map.jacobian.transpose() * dv;
    for (std::size_t k = 0; k < map.global.size(); ++k)
      triplets.emplace_back(map.global[k], s, local[k]);
  }
  Eigen::SparseMatrix<double> d(num_dofs_, num_segments());
  d.setFromTriplets(triplets.begin(), triplets.end());
  return d;
}

}  // namespace xshell
