#include "statics_problem.hpp"

#include <algorithm>
#include <vector>

#include "model_error.hpp"
#include "segment_parallel.hpp"

namespace xshell {

namespace {
// Angle from the old to the new reference direction of an edge, as the edge
// moves with velocity de: the rate at which theta must change for the
// material frame to move the same way with the new source frame.
double theta_rate_correction(const Eigen::Vector3d& e, const Eigen::Vector3d& de,
                             const SourceFrame& old_source, const SourceFrame& new_source) {
  using D = Dual<1>;
  const D tau = D::variable(0, 0.0);
  const V3<D> edge = lift<D>(e) + lift<D>(de) * tau;
  const V3<D> t = edge / norm(edge);
  const Frame<D> a = reference_frame(t, new_source);
  const Frame<D> b = reference_frame(t, old_source);
  return signed_angle(a.d1, b.d1, t).g[0];
}
}  // namespace

Eigen::VectorXd LinkageProblem::free_dofs() const {
  const Eigen::VectorXd r = linkage_.dofs();
  Eigen::VectorXd q(free_.size());
  for (size_t i = 0; i < free_.size(); ++i) q[i] = r[free_[i]];
  return q;
}

Eigen::VectorXd LinkageProblem::with_fixed_zero(const Eigen::VectorXd& q) const {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(linkage_.num_dofs());
  for (size_t i = 0; i < free_.size(); ++i) r[free_[i]] = q[i];
  return r;
}

Eigen::VectorXd LinkageProblem::dofs_with_free(const Eigen::VectorXd& q) const {
  Eigen::VectorXd r = linkage_.dofs();
  for (size_t i = 0; i < free_.size(); ++i) r[free_[i]] = q[i];
  return r;
}

void LinkageProblem::set_free_dofs(const Eigen::VectorXd& q) {
  ++version_;
  linkage_.set_dofs(dofs_with_free(q));
}

void LinkageProblem::set_segment_rest_lengths(const std::vector<double>& lengths) {
  if (rest_length_loads_)
    throw ModelError(
        "segment rest lengths: the problem has gravity or line loads, which are lumped on the rest "
        "lengths; changing them under such loads is not supported");
  ++version_;
  linkage_.set_segment_rest_lengths(lengths);
}

double LinkageProblem::set_free_dofs_and_energy(const Eigen::VectorXd& q) {
  ++version_;
  RodEnergy elastic;
  linkage_.set_dofs(dofs_with_free(q), &elastic);
  return energy_with(elastic).total();
}

EnergyReport LinkageProblem::energy() const { return energy_with(linkage_.energy()); }

EnergyReport LinkageProblem::energy_with(const RodEnergy& e) const {
  EnergyReport report{e.stretching, e.bending, e.twisting, 0.0};
  // Work of the dead loads: per segment in parallel, summed in order.
  std::vector<double> work(linkage_.num_segments(), 0.0);
  for_each_segment(linkage_.num_segments(), [&](int s) {
    if (has_segment_loads_[s])
      work[s] =
          segment_forces_[s].dot(linkage_.segment(s).dofs() - linkage_.input_segment_dofs()[s]);
  });
  for (double w : work) report.external -= w;
  if (has_point_loads_) report.external -= point_forces_.dot(linkage_.dofs() - input_dofs_);
  return report;
}

void LinkageProblem::remove_loads_along(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d b = direction.normalized();
  const auto remove = [&b](auto&& f) { f -= f.dot(b) * b; };
  restore_loads();
  for (int s = 0; s < linkage_.num_segments(); ++s)
    for (int n = 0; n < linkage_.segment(s).num_nodes(); ++n)
      remove(segment_forces_[s].segment<3>(ElasticRod::node_dof(n)));
  for (int j = 0; j < linkage_.num_joints(); ++j)
    remove(point_forces_.segment<3>(linkage_.joint_dof_offset(j) + kPosition));
}

void LinkageProblem::scale_loads(double factor) {
  for (size_t s = 0; s < segment_forces_.size(); ++s)
    segment_forces_[s] = factor * given_segment_forces_[s];
  point_forces_ = factor * given_point_forces_;
  ++version_;
}

double LinkageProblem::load_along(const Eigen::Vector3d& direction) const {
  double sum = 0.0;
  for (int s = 0; s < linkage_.num_segments(); ++s)
    for (int n = 0; n < linkage_.segment(s).num_nodes(); ++n)
      sum += given_segment_forces_[s].segment<3>(ElasticRod::node_dof(n)).dot(direction);
  for (int j = 0; j < linkage_.num_joints(); ++j)
    sum += given_point_forces_.segment<3>(linkage_.joint_dof_offset(j) + kPosition).dot(direction);
  return sum;
}

Eigen::VectorXd LinkageProblem::full_gradient() const {
  if (gradient_version_ != version_) {
    if (!assembly_.matches(linkage_, free_position_))
      assembly_ = LinkageAssembly(linkage_, free_position_);
    assembly_.gradient(linkage_, &segment_forces_, gradient_);
    gradient_ -= point_forces_;
    gradient_version_ = version_;
  }
  return gradient_;
}

Eigen::VectorXd LinkageProblem::free_gradient() const {
  const Eigen::VectorXd g = full_gradient();
  Eigen::VectorXd out(free_.size());
  for (size_t i = 0; i < free_.size(); ++i) out[i] = g[free_[i]];
  return out;
}

const Eigen::SparseMatrix<double>& LinkageProblem::free_hessian() {
  if (hessian_version_ == version_) return hessian_;
  if (!assembly_.matches(linkage_, free_position_))
    assembly_ = LinkageAssembly(linkage_, free_position_);
  assembly_.hessian(linkage_, &segment_forces_, hessian_, &gradient_,
                    mixed_hessian() ? &hessian_axial_forces_ : nullptr);
  gradient_ -= point_forces_;
  gradient_version_ = hessian_version_ = version_;
  return hessian_;
}

void LinkageProblem::use_mixed_hessian(const Eigen::VectorXd& p) {
  const Eigen::VectorXd v = with_fixed_zero(p);
  std::vector<Eigen::VectorXd> forces(linkage_.num_segments());
  double change = 0.0;
  for (int s = 0; s < linkage_.num_segments(); ++s) {
    const Eigen::VectorXd segment_velocity = linkage_.full_velocity(s, v);
    forces[s] = linkage_.segment(s).linearized_axial_forces(segment_velocity);
    change = std::max(change, linkage_.segment(s).largest_edge_change(segment_velocity));
  }
  if (change <= kNegligibleEdgeChange) {
    use_exact_hessian();
    return;
  }
  hessian_axial_forces_ = std::move(forces);
  hessian_version_ = -1;
}

void LinkageProblem::use_exact_hessian() {
  if (!mixed_hessian()) return;
  hessian_axial_forces_.clear();
  hessian_version_ = -1;
}

Eigen::VectorXd LinkageProblem::gradient_weights() const {
  Eigen::VectorXd w_all = Eigen::VectorXd::Constant(linkage_.num_dofs(), 1.0 / force_scale_);
  const double moment = 1.0 / (length_scale_ * force_scale_);
  for (int s = 0; s < linkage_.num_segments(); ++s) {
    const ElasticRod& rod = linkage_.segment(s);
    for (int j = 0; j < rod.num_edges(); ++j) {
      const int r = linkage_.reduced_index(s, rod.theta_dof(j));
      if (r >= 0) w_all[r] = moment;
    }
  }
  for (int j = 0; j < linkage_.num_joints(); ++j) {
    // Edge-vector joints: p and both edge vectors are positions (forces).
    if (linkage_.joint(j).kind() != JointKind::Rotation) continue;
    const int o = linkage_.joint_dof_offset(j);
    for (int c = 0; c < 4; ++c) w_all[o + kOmega + c] = moment;  // omega (3) and alpha
  }
  Eigen::VectorXd w(free_.size());
  for (size_t i = 0; i < free_.size(); ++i) w[i] = w_all[free_[i]];
  return w;
}

double LinkageProblem::gradient_measure() const {
  if (free_.empty()) return 0.0;
  return (gradient_weights().array() * free_gradient().array()).abs().maxCoeff();
}

Eigen::VectorXd LinkageProblem::free_mass() const {
  bool unit = false;
  for (int s = 0; s < linkage_.num_segments(); ++s)
    unit = unit || linkage_.segment_material(s).density <= 0.0;
  const Eigen::VectorXd m = linkage_.lumped_mass(unit);
  Eigen::VectorXd out(free_.size());
  for (size_t i = 0; i < free_.size(); ++i) out[i] = m[free_[i]];
  return out;
}

void LinkageProblem::rebase(Eigen::VectorXd* free_velocity) {
  ++version_;
  if (!free_velocity) {
    linkage_.update_source_frames();
    linkage_.fold_joints();
    return;
  }
  Eigen::VectorXd v = with_fixed_zero(*free_velocity);
  // Edge velocities and old source frames, before the update.
  std::vector<Eigen::VectorXd> full_velocity;
  std::vector<std::vector<SourceFrame>> old_sources;
  for (int s = 0; s < linkage_.num_segments(); ++s) {
    full_velocity.push_back(linkage_.full_velocity(s, v));
    old_sources.push_back(linkage_.segment(s).source_frames());
  }
  std::vector<Eigen::Matrix3d> jacobians;
  for (int j = 0; j < linkage_.num_joints(); ++j)
    jacobians.push_back(linkage_.joint(j).kind() == JointKind::Rotation
                            ? left_jacobian(linkage_.joint(j).params().segment<3>(kOmega))
                            : Eigen::Matrix3d::Identity());
  linkage_.update_source_frames();
  linkage_.fold_joints();
  for (int s = 0; s < linkage_.num_segments(); ++s) {
    const ElasticRod& rod = linkage_.segment(s);
    for (int j = 0; j < rod.num_edges(); ++j) {
      const int r = linkage_.reduced_index(s, rod.theta_dof(j));
      if (r < 0) continue;
      const Eigen::Vector3d de =
          full_velocity[s].segment<3>(3 * (j + 1)) - full_velocity[s].segment<3>(3 * j);
      v[r] += theta_rate_correction(rod.edge(j), de, old_sources[s][j], rod.source_frames()[j]);
    }
  }
  for (int j = 0; j < linkage_.num_joints(); ++j) {
    if (linkage_.joint(j).kind() != JointKind::Rotation) continue;  // nothing folded
    const int o = linkage_.joint_dof_offset(j) + kOmega;
    v.segment<3>(o) = jacobians[j] * v.segment<3>(o);
  }
  for (size_t i = 0; i < free_.size(); ++i) (*free_velocity)[i] = v[free_[i]];
}

std::vector<Eigen::Vector3d> LinkageProblem::vertex_positions() const {
  std::vector<Eigen::Vector3d> out;
  for (size_t v = 0; v < linkage_.graph().vertices.size(); ++v)
    out.push_back(linkage_.vertex_position(static_cast<int>(v)));
  return out;
}

std::vector<std::optional<double>> LinkageProblem::opening_angles() const {
  std::vector<std::optional<double>> out(linkage_.graph().vertices.size());
  for (int j = 0; j < linkage_.num_joints(); ++j)
    out[linkage_.topology().joints[j].vertex] = linkage_.joint(j).opening_angle();
  return out;
}

}  // namespace xshell
