#include "reactions.hpp"

#include <Eigen/LU>

namespace xshell {

namespace {

// Moment about the vertex of a rigid rotation of the free end's clamped
// edge, whose midpoint the vertex is (header).
Eigen::Vector3d clamp_moment(const ElasticRod& rod, int edge, bool at_start,
                             const Eigen::Vector3d& g_end, const Eigen::Vector3d& g_next,
                             double g_theta) {
  const Eigen::Vector3d e = at_start ? rod.edge(edge) : Eigen::Vector3d(-rod.edge(edge));
  const Eigen::Vector3d t = rod.tangent(edge);  // the theta's edge, in its own direction
  const Eigen::Vector3d t_source = rod.source_frames()[edge].tangent;
  const Eigen::Vector3d kh = 2.0 * t_source.cross(t) / (1.0 + t_source.dot(t));
  return 0.5 * e.cross(Eigen::Vector3d(g_next - g_end)) + g_theta * (t + 0.5 * t.cross(kh));
}

// The reaction at a free rod end f from the total energy's gradient g:
// the held components of the end node's force, or at a clamped end the
// force and moment of the whole clamped edge (header).
void free_end_reaction(const LinkageProblem& problem, const Eigen::VectorXd& g,
                       const RodLinkage::FreeEnd& f, SupportReaction& r) {
  const RodLinkage& l = problem.linkage();
  const ElasticRod& rod = l.segment(f.segment);
  auto reduced_gradient = [&](int full) { return g[l.reduced_index(f.segment, full)]; };
  Eigen::Vector3d g_end, g_next;
  for (int c = 0; c < 3; ++c) g_end[c] = reduced_gradient(3 * f.end_node + c);
  if (!f.clamped) {
    for (int c = 0; c < 3; ++c) {
      const int i = l.reduced_index(f.segment, 3 * f.end_node + c);
      if (i >= 0 && problem.is_fixed(i)) r.force[c] = g_end[c];
    }
    return;
  }
  for (int c = 0; c < 3; ++c) g_next[c] = reduced_gradient(3 * f.next_node + c);
  r.force = g_end + g_next;
  r.moment =
      clamp_moment(rod, f.edge, f.at_start, g_end, g_next, reduced_gradient(rod.theta_dof(f.edge)));
}

}  // namespace

std::vector<SupportReaction> support_reactions(const LinkageProblem& problem) {
  const RodLinkage& l = problem.linkage();
  const Eigen::VectorXd g = problem.full_gradient();
  std::vector<SupportReaction> out;
  auto entry = [&](int vertex) -> SupportReaction& {
    for (SupportReaction& r : out)
      if (r.vertex == vertex) return r;
    SupportReaction r;
    r.vertex = vertex;
    r.position = l.vertex_position(vertex);
    out.push_back(r);
    return out.back();
  };
  for (const VertexSupport& support : problem.supports()) {
    SupportReaction& r = entry(support.vertex);
    const int j = l.topology().joint_of_vertex[support.vertex];
    if (j >= 0) {
      const Joint& joint = l.joint(j);
      const int o = l.joint_dof_offset(j);
      for (int c = 0; c < 3; ++c)
        if (problem.is_fixed(o + kPosition + c)) r.force[c] = g[o + kPosition + c];
      for (SupportDof dof : support.fix) {
        if (dof == SupportDof::OpeningAngle) r.opening_torque = g[o + kAlpha];
        if (dof != SupportDof::Orientation) continue;
        if (joint.kind() == JointKind::Rotation) {
          const Eigen::Matrix3d jl = left_jacobian(joint.params().segment<3>(kOmega));
          r.moment = jl.transpose().lu().solve(Eigen::Vector3d(g.segment<3>(o + kOmega)));
        } else {
          Eigen::Vector3d m = Eigen::Vector3d::Zero();
          for (int x = 0; x < 2; ++x) {
            const int base = x == 0 ? kEdgeA : kEdgeB;
            const Eigen::Vector3d g_edge = joint.edge_basis(x) * g.segment<3>(o + base);
            m += joint.edge(x).cross(g_edge);
          }
          r.moment = m;
        }
      }
      continue;
    }
    free_end_reaction(problem, g, l.free_end(support.vertex), r);
  }
  return out;
}

Wrench applied_load_resultant(const LinkageProblem& problem) {
  const RodLinkage& l = problem.linkage();
  Wrench w;
  for (int s = 0; s < l.num_segments(); ++s) {
    const ElasticRod& rod = l.segment(s);
    const Eigen::VectorXd& f = problem.segment_loads()[s];
    for (int n = 0; n < rod.num_nodes(); ++n) {
      const Eigen::Vector3d fn = f.segment<3>(3 * n);
      w.force += fn;
      w.moment += rod.nodes()[n].cross(fn);
    }
  }
  for (int j = 0; j < l.num_joints(); ++j) {
    const Eigen::Vector3d fj = problem.joint_loads().segment<3>(l.joint_dof_offset(j) + kPosition);
    w.force += fj;
    w.moment += l.joint(j).position().cross(fj);
  }
  return w;
}

Wrench reaction_resultant(const std::vector<SupportReaction>& reactions) {
  Wrench w;
  for (const SupportReaction& r : reactions) {
    w.force += r.force;
    w.moment += r.position.cross(r.force);
    if (r.moment) w.moment += *r.moment;
  }
  return w;
}

}  // namespace xshell
