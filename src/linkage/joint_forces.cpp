#include "joint_forces.hpp"

#include <Eigen/LU>

namespace xshell {

std::vector<JointForce> joint_forces(const LinkageProblem& problem) {
  const RodLinkage& l = problem.linkage();
  // Gradient of each segment's energy minus the work of its loads, on its
  // full variables.
  std::vector<Eigen::VectorXd> gradients(l.num_segments());
  for (int s = 0; s < l.num_segments(); ++s)
    gradients[s] = l.segment(s).gradient() - problem.segment_loads()[s];

  std::vector<JointForce> out;
  for (int j = 0; j < l.num_joints(); ++j) {
    const JointTopology& jt = l.topology().joints[j];
    const Joint& joint = l.joint(j);
    JointForce f;
    f.vertex = jt.vertex;
    f.rod = jt.rod;
    std::array<Eigen::Vector3d, 2> g_omega{{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
    for (int x = 0; x < 2; ++x)
      for (const SegmentEnd& end : jt.ends[x]) {
        const ElasticRod& rod = l.segment(end.segment);
        const SegmentTopology& seg = l.topology().segments[end.segment];
        const int side = end.at_start ? 0 : 1;
        const int edge = terminal_edge_index(rod, side);
        const Eigen::VectorXd& g = gradients[end.segment];
        Eigen::Matrix<double, 7, 1> g_terminal;
        g_terminal << g.segment<3>(3 * edge), g.segment<3>(3 * (edge + 1)), g[rod.theta_dof(edge)];
        Eigen::Matrix<double, 7, 9> jacobian;
        terminal_edge_jacobian(joint, seg.label[side], seg.sign[side], rod.source_frames()[edge],
                               rod.thetas()[edge], jacobian);
        const Eigen::Matrix<double, 9, 1> g_joint = jacobian.transpose() * g_terminal;
        f.force_on[x] += g_joint.segment<3>(kPosition);
        g_omega[x] += g_joint.segment<3>(kOmega);
      }
    if (joint.kind() == JointKind::Rotation) {
      const Eigen::Matrix3d jl_t = left_jacobian(joint.params().segment<3>(kOmega)).transpose();
      f.moment_on = std::array<Eigen::Vector3d, 2>{
          {jl_t.lu().solve(g_omega[0]), jl_t.lu().solve(g_omega[1])}};
    }
    out.push_back(f);
  }
  return out;
}

}  // namespace xshell
