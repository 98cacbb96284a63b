#include "rod_stresses.hpp"

#include <cmath>

namespace xshell {

LinkageStresses linkage_stresses(const RodLinkage& linkage) {
  LinkageStresses out;
  auto consider = [&](EdgeLocation& best, double value, int s, int j) {
    if (best.segment >= 0 && value <= best.value) return;
    const ElasticRod& rod = linkage.segment(s);
    best = {value, s, j, linkage.topology().segments[s].rod,
            0.5 * (rod.nodes()[j] + rod.nodes()[j + 1])};
  };
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const ElasticRod& rod = linkage.segment(s);
    const Material& material = linkage.segment_material(s);
    const SectionModuli moduli = section_moduli(material.section);
    std::vector<EdgeStress> edges;
    const std::vector<SectionForces> forces = edge_forces(rod);
    for (int j = 0; j < rod.num_edges(); ++j) {
      EdgeStress e;
      e.forces = forces[j];
      e.stresses = section_stresses(moduli, e.forces);
      e.equivalent = std::sqrt(e.stresses.max_normal * e.stresses.max_normal +
                               3.0 * e.stresses.torsional_shear * e.stresses.torsional_shear);
      consider(out.max_normal_stress, e.stresses.max_normal, s, j);
      consider(out.max_torsional_shear, e.stresses.torsional_shear, s, j);
      consider(out.max_axial_force, std::abs(e.forces.axial), s, j);
      if (material.strength > 0.0) {
        e.utilisation = e.equivalent / material.strength;
        if (!out.max_utilisation) out.max_utilisation = EdgeLocation{};
        consider(*out.max_utilisation, *e.utilisation, s, j);
      }
      edges.push_back(e);
    }
    out.segments.push_back(std::move(edges));
  }
  return out;
}

}  // namespace xshell
