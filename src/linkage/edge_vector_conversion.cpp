#include "edge_vector_conversion.hpp"

#include <stdexcept>

namespace xshell {

JointEdgeVectors edge_vectors(const Joint& joint) {
  return {joint.position(), joint.edge(0), joint.edge(1)};
}

Joint joint_from_edge_vectors(const JointEdgeVectors& g, JointKind kind) {
  const double l_a = g.e_a.norm(), l_b = g.e_b.norm();
  const Eigen::Vector3d c = g.e_a.cross(g.e_b);
  if (!(l_a > 0.0 && l_b > 0.0 && c.norm() > 0.0))
    throw std::domain_error("joint conversion: the edge vectors must be nonzero and not parallel");
  if (kind == JointKind::EdgeVectors && nearly_parallel(g.e_a, g.e_b))
    throw std::domain_error(
        "joint conversion: the edge vectors are too close to parallel for an edge-vector joint");
  return Joint(g.p, g.e_a / l_a, g.e_b / l_b, c.normalized(), l_a, l_b, kind);
}

Joint convert_joint(const Joint& joint, JointKind kind) {
  if (joint.kind() == kind) return joint;
  const JointEdgeVectors g = edge_vectors(joint);
  if (joint.kind() == JointKind::Rotation && g.e_a.cross(g.e_b).dot(joint.normal()) <= 0.0)
    throw std::domain_error("joint conversion: the rotation joint opens beyond (0, pi)");
  return joint_from_edge_vectors(g, kind);
}

}  // namespace xshell
