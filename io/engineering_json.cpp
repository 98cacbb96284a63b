#include "engineering_json.hpp"

#include "optional_json.hpp"

namespace xshell {

namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json location(const EdgeLocation& l, const Eigen::Vector3d& origin) {
  return {{"value", l.value},
          {"rod", l.rod},
          {"segment", l.segment},
          {"edge", l.edge},
          {"position", vec(l.midpoint + origin)}};
}

}  // namespace

nlohmann::json engineering_json(const EngineeringResults& r, const Eigen::Vector3d& origin) {
  using nlohmann::json;
  json reactions = json::array();
  for (const SupportReaction& s : r.reactions)
    reactions.push_back({{"vertex", s.vertex},
                         {"position", vec(s.position + origin)},
                         {"force", vec(s.force)},
                         {"moment", s.moment ? vec(*s.moment) : json(nullptr)},
                         {"opening_torque", optional_json(s.opening_torque)}});
  const LinkageStresses& st = r.stresses;
  json stresses = {{"max_normal_stress", location(st.max_normal_stress, origin)},
                   {"max_torsional_shear", location(st.max_torsional_shear, origin)},
                   {"max_axial_force", location(st.max_axial_force, origin)},
                   {"max_utilisation",
                    st.max_utilisation ? location(*st.max_utilisation, origin) : json(nullptr)}};
  json joints = json::array();
  for (const JointForce& j : r.joint_forces)
    joints.push_back({{"vertex", j.vertex},
                      {"rods", {j.rod[0], j.rod[1]}},
                      {"force_on_a", vec(j.force_on[0])},
                      {"force_on_b", vec(j.force_on[1])},
                      {"moment_on_a", j.moment_on ? vec((*j.moment_on)[0]) : json(nullptr)},
                      {"moment_on_b", j.moment_on ? vec((*j.moment_on)[1]) : json(nullptr)}});
  json out = {{"reactions", reactions}, {"stresses", stresses}, {"joint_forces", joints}};
  if (const auto& s = r.stability) {
    out["lowest_eigenvalues"] = s->lowest_eigenvalues;
    out["buckling_load_factor"] = optional_json(s->buckling_load_factor);
    out["stability_analysis"] = {{"eigenvalues", s->eigen_status},
                                 {"buckling", s->buckling_status}};
  }
  return out;
}

}  // namespace xshell
