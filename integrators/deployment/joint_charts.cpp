#include "integrators/deployment/joint_charts.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "math/rotation.hpp"

namespace xshell {

std::vector<FreeRotation> free_rotations(const LinkageProblem& problem) {
  const RodLinkage& linkage = problem.linkage();
  std::vector<FreeRotation> rotations;
  for (int j = 0; j < linkage.num_joints(); ++j) {
    if (linkage.joint(j).kind() != JointKind::Rotation) continue;
    FreeRotation r;
    r.joint = j;
    for (int k = 0; k < 3; ++k)
      r.free[k] = problem.free_position(linkage.joint_dof_offset(j) + kOmega + k);
    if (*std::min_element(r.free.begin(), r.free.end()) >= 0) rotations.push_back(r);
  }
  return rotations;
}

std::vector<Eigen::Matrix3d> joint_frames(const RodLinkage& linkage,
                                          const std::vector<FreeRotation>& rotations) {
  std::vector<Eigen::Matrix3d> frames;
  frames.reserve(rotations.size());
  for (const FreeRotation& r : rotations) {
    const Joint& joint = linkage.joint(r.joint);
    frames.push_back(rotation_matrix(joint.params().segment<3>(kOmega)) * joint.reference_frame());
  }
  return frames;
}

namespace {

Eigen::Vector3d gather(const Eigen::VectorXd& v, const FreeRotation& r) {
  return {v[r.free[0]], v[r.free[1]], v[r.free[2]]};
}

void scatter(const Eigen::Vector3d& w, const FreeRotation& r, Eigen::VectorXd& v) {
  for (int k = 0; k < 3; ++k) v[r.free[k]] = w[k];
}

}  // namespace

PathPoint in_current_charts(const PathPoint& point, const RodLinkage& linkage,
                            const std::vector<FreeRotation>& rotations) {
  PathPoint out = point;
  const bool tangent = point.tangent.size() == point.q.size();
  for (size_t i = 0; i < rotations.size(); ++i) {
    const FreeRotation& r = rotations[i];
    const Eigen::Matrix3d relative =
        point.frames[i] * linkage.joint(r.joint).reference_frame().transpose();
    const Eigen::AngleAxisd angle_axis(relative);
    const Eigen::Vector3d omega = angle_axis.angle() * angle_axis.axis();
    scatter(omega, r, out.q);
    if (!tangent) continue;
    const Eigen::Vector3d spatial = left_jacobian(gather(point.q, r)) * gather(point.tangent, r);
    scatter(left_jacobian(omega).lu().solve(spatial), r, out.tangent);
  }
  return out;
}

}  // namespace xshell
