// Random rods for the rod tests.
#pragma once

#include <random>

#include "finite_differences.hpp"
#include "rod/elastic_rod.hpp"

namespace xshell::test {

inline RodStiffness anisotropic_stiffness() {
  Material m;
  m.young_modulus = 200.0;
  m.poisson_ratio = 0.3;
  m.section = {SectionShape::Rectangle, 0.12, 0.05};
  return stiffness(m);
}

// A rod at rest in a curved, twisted state: random polyline, random thetas.
inline ElasticRod random_curved_rod(int edges, std::mt19937& rng, const RodStiffness& k) {
  std::vector<Eigen::Vector3d> nodes(edges + 1);
  Eigen::Vector3d direction(1.0, 0.2, 0.0);
  nodes[0] = Eigen::Vector3d::Zero();
  for (int i = 1; i <= edges; ++i) {
    direction = (direction + 0.5 * random_vector(3, rng)).normalized();
    nodes[i] = nodes[i - 1] + (0.8 + 0.4 * random_vector(1, rng, 0.5)[0]) * direction;
  }
  ElasticRod rod(nodes, k);
  std::vector<double> thetas(edges);
  for (double& t : thetas) t = random_vector(1, rng, 1.0)[0];
  rod.set_configuration(nodes, thetas);
  rod.set_rest_state_from_current();
  return rod;
}

// Perturbs every node and theta of a rod.
inline void perturb(ElasticRod& rod, std::mt19937& rng, double amplitude) {
  rod.set_dofs(rod.dofs() + random_vector(rod.num_dofs(), rng, amplitude));
}

}  // namespace xshell::test
