#include "rest_scale_derivatives.hpp"

#include "stretching.hpp"

namespace xshell {

double rest_scale_energy_derivative(const ElasticRod& rod) {
  const RodEnergy e = rod.energy();
  double d = -(e.bending + e.twisting);
  for (int j = 0; j < rod.num_edges(); ++j) {
    const double l = rod.rest_lengths()[j];
    const double k = rod.stiffness().stretching * rod.stretching_share(j);
    const double ratio = rod.edge(j).norm() / l;
    d -= 0.5 * k * (ratio * ratio - 1.0) * l;
  }
  return d;
}

Eigen::VectorXd rest_scale_gradient_derivative(const ElasticRod& rod) {
  // The bending and twisting gradient is the whole gradient less the
  // stretching one, so that d/dlambda = d(stretching)/dlambda - (g - g_s).
  Eigen::VectorXd d = -rod.gradient();
  for (int j = 0; j < rod.num_edges(); ++j) {
    const double l = rod.rest_lengths()[j];
    const double k = rod.stiffness().stretching * rod.stretching_share(j);
    const Eigen::Vector3d e = rod.edge(j);
    const Eigen::Vector3d stretching = stretching_gradient(e, l, k);
    const Eigen::Vector3d scaled = -k * e / l;
    // +g_s (undoing its share in -g) + its derivative, with de/dx_j = -I,
    // de/dx_{j+1} = I.
    const Eigen::Vector3d edge_term = stretching + scaled;
    d.segment<3>(ElasticRod::node_dof(j)) -= edge_term;
    d.segment<3>(ElasticRod::node_dof(j + 1)) += edge_term;
  }
  return d;
}

}  // namespace xshell
