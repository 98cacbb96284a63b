#include "engineering_snapshot.hpp"

#include "linkage_snapshot.hpp"

namespace xshell {

EngineeringSnapshot engineering_snapshot(const RodLinkage& linkage,
                                         const EngineeringResults& results,
                                         const Eigen::Vector3d& origin) {
  EngineeringSnapshot out;
  for (const SupportReaction& r : results.reactions)
    out.reactions.push_back({r.vertex, r.position + origin, r.force,
                             r.moment ? *r.moment : Eigen::Vector3d(Eigen::Vector3d::Zero())});
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const ElasticRod& rod = linkage.segment(s);
    std::vector<Eigen::Vector3d> nodes;
    for (const Eigen::Vector3d& x : rod.nodes()) nodes.push_back(x + origin);
    if (s < static_cast<int>(results.stresses.segments.size()))
      for (int j = 0; j < rod.num_edges(); ++j) {
        const EdgeStress& e = results.stresses.segments[s][j];
        EdgeResult r;
        r.a = nodes[j];
        r.b = nodes[j + 1];
        r.rod_id = linkage.topology().segments[s].rod;
        r.segment_id = s;
        r.axial_force = e.forces.axial;
        r.bending_moment1 = e.forces.moment1;
        r.bending_moment2 = e.forces.moment2;
        r.torque = e.forces.torque;
        r.axial_stress = e.stresses.axial;
        r.bending_stress1 = e.stresses.bending1;
        r.bending_stress2 = e.stresses.bending2;
        r.torsional_shear = e.stresses.torsional_shear;
        r.max_normal_stress = e.stresses.max_normal;
        r.equivalent_stress = e.equivalent;
        r.utilisation = e.utilisation ? *e.utilisation : -1.0;
        out.edges.push_back(r);
      }
    out.segment_nodes.push_back(std::move(nodes));
  }
  out.joints = linkage_snapshot(linkage, origin, 0.0);
  out.joints.rods.clear();
  for (size_t j = 0; j < out.joints.joints.size() && j < results.joint_forces.size(); ++j) {
    out.joints.joints[j].pin_force_a = results.joint_forces[j].force_on[0];
    out.joints.joints[j].pin_force_b = results.joint_forces[j].force_on[1];
  }
  return out;
}

}  // namespace xshell
