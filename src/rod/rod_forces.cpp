#include "rod_forces.hpp"

#include "stretching.hpp"

namespace xshell {

SectionForces vertex_moments(const ElasticRod& rod, int i) {
  const VertexStrains<double> k = rod.strains(i);
  const auto& rest = rod.rest_kappa(i);
  const RodStiffness& s = rod.stiffness();
  const double v = rod.voronoi_length(i);
  SectionForces f;
  for (int j = 0; j < 2; ++j) {
    f.moment1 += 0.5 * s.bending1 * (k.kappa[j][0] - rest[j][0]) / v;
    f.moment2 += 0.5 * s.bending2 * (k.kappa[j][1] - rest[j][1]) / v;
  }
  f.torque = s.twisting * (k.twist - rod.rest_twist(i)) / v;
  return f;
}

std::vector<SectionForces> edge_forces(const ElasticRod& rod) {
  const int n = rod.num_edges();
  std::vector<SectionForces> vertex(n + 1);
  for (int i = 1; i < n; ++i) vertex[i] = vertex_moments(rod, i);
  std::vector<SectionForces> out(n);
  for (int j = 0; j < n; ++j) {
    SectionForces& f = out[j];
    f.axial = axial_force(rod.edge(j), rod.rest_lengths()[j], rod.stiffness().stretching);
    int count = 0;
    for (int i : {j, j + 1}) {
      if (i < 1 || i > n - 1) continue;
      f.moment1 += vertex[i].moment1;
      f.moment2 += vertex[i].moment2;
      f.torque += vertex[i].torque;
      ++count;
    }
    if (count > 0) {
      f.moment1 /= count;
      f.moment2 /= count;
      f.torque /= count;
    }
  }
  return out;
}

}  // namespace xshell
