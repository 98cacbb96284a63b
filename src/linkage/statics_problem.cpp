#include "statics_problem.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "model_error.hpp"
#include "segment_parallel.hpp"

namespace xshell {

namespace {
std::string vertex_name(int v) { return "vertex " + std::to_string(v); }

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

LinkageProblem::LinkageProblem(RodLinkage linkage, const StaticsSetup& setup)
    : linkage_(std::move(linkage)) {
  const RodLinkage& l = linkage_;
  const int nv = static_cast<int>(l.graph().vertices.size());
  fixed_.assign(l.num_dofs(), false);

  // Scales.
  Eigen::Vector3d lo = l.graph().vertices[0], hi = lo;
  for (const auto& v : l.graph().vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  length_scale_ = (hi - lo).norm();
  double bending_max = 0.0;
  for (int s = 0; s < l.num_segments(); ++s)
    bending_max = std::max(
        {bending_max, l.segment(s).stiffness().bending1, l.segment(s).stiffness().bending2});
  force_scale_ = bending_max / (length_scale_ * length_scale_);

  // Supports.
  auto check_vertex = [&](int v, const char* what) {
    if (v < 0 || v >= nv)
      throw ModelError(std::string(what) + " names " + vertex_name(v) + ", but the linkage has " +
                       std::to_string(nv) + " vertices");
  };
  std::vector<VertexSupport> supports = setup.supports;
  if (supports.empty()) {
    if (l.num_joints() == 0)
      throw ModelError(
          "the linkage has no joint to pin by default: give supports that hold it in place");
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    int best = -1;
    for (int j = 0; j < l.num_joints(); ++j) {
      const int v = l.topology().joints[j].vertex;
      if (best < 0 || (l.graph().vertices[v] - centre).norm() <
                          (l.graph().vertices[best] - centre).norm() - 1e-12 * length_scale_)
        best = v;
    }
    default_support_ = best;
    supports.push_back({best, {SupportDof::Position, SupportDof::Orientation}});
  }
  // Prescribed displacements: the held position components move to input +
  // displacement (the input: the graph's vertex, or a free end's input nodes).
  Eigen::VectorXd displaced = linkage_.dofs();
  for (const VertexSupport& support : supports) {
    check_vertex(support.vertex, "a support");
    if (!support.displacement.allFinite())
      throw ModelError("support at " + vertex_name(support.vertex) +
                       ": the displacement is not finite");
    if (support.displacement.isZero(0.0)) continue;
    bool held[3] = {false, false, false};
    bool clamped = false;
    for (SupportDof dof : support.fix) {
      if (dof == SupportDof::Position) held[0] = held[1] = held[2] = true;
      if (dof == SupportDof::X) held[0] = true;
      if (dof == SupportDof::Y) held[1] = true;
      if (dof == SupportDof::Z) held[2] = true;
      if (dof == SupportDof::Orientation) clamped = true;
    }
    for (int c = 0; c < 3; ++c)
      if (support.displacement[c] != 0.0 && !held[c])
        throw ModelError("support at " + vertex_name(support.vertex) +
                         ": its displacement moves the " + std::string(1, char('x' + c)) +
                         " component, which the support does not hold (fix \"position\" or \"" +
                         std::string(1, char('x' + c)) + "\")");
    const int j = l.topology().joint_of_vertex[support.vertex];
    if (j >= 0) {
      const int o = l.joint_dof_offset(j) + kPosition;
      for (int c = 0; c < 3; ++c)
        if (held[c])
          displaced[o + c] = l.graph().vertices[support.vertex][c] + support.displacement[c];
      continue;
    }
    const RodLinkage::FreeEnd f = l.free_end(support.vertex);
    const int s = f.segment, end = f.end_node, next = f.next_node;
    const Eigen::VectorXd& input = l.input_segment_dofs()[s];
    for (int node : {end, next}) {
      if (node == next && !clamped) continue;
      for (int c = 0; c < 3; ++c) {
        const int r = l.reduced_index(s, 3 * node + c);
        if (held[c] && r >= 0) displaced[r] = input[3 * node + c] + support.displacement[c];
      }
    }
  }
  linkage_.set_dofs(displaced);

  for (const VertexSupport& support : supports) {
    const int j = l.topology().joint_of_vertex[support.vertex];
    for (SupportDof dof : support.fix) {
      if (j >= 0) {
        const int o = l.joint_dof_offset(j);
        if (l.joint(j).kind() == JointKind::EdgeVectors && dof == SupportDof::Orientation) {
          // The seed's constrained joint: directions fixed, lengths free.
          linkage_.align_joint(j);
          for (int base : {kEdgeA, kEdgeB})
            for (int c = 1; c < 3; ++c) fix(o + base + c);
          continue;
        }
        if (l.joint(j).kind() == JointKind::EdgeVectors && dof == SupportDof::OpeningAngle)
          throw ModelError(
              "support at " + vertex_name(support.vertex) +
              ": edge-vector joints have no opening-angle unknown; fix \"orientation\" (both rod "
              "directions, hence the angle too) or use rotation joints");
        switch (dof) {
          case SupportDof::Position:
            for (int c = 0; c < 3; ++c) fix(o + kPosition + c);
            break;
          case SupportDof::X:
            fix(o + kPosition);
            break;
          case SupportDof::Y:
            fix(o + kPosition + 1);
            break;
          case SupportDof::Z:
            fix(o + kPosition + 2);
            break;
          case SupportDof::Orientation:
            for (int c = 0; c < 3; ++c) fix(o + kOmega + c);
            break;
          case SupportDof::OpeningAngle:
            fix(o + kAlpha);
            break;
        }
        continue;
      }
      const RodLinkage::FreeEnd f = l.free_end(support.vertex);
      const int s = f.segment, end = f.end_node, next = f.next_node, edge = f.edge;
      const ElasticRod& rod = l.segment(s);
      auto fix_full = [&](int full) {
        const int r = l.reduced_index(s, full);
        if (r < 0)
          throw ModelError("support at " + vertex_name(support.vertex) +
                           ": the end edge is too short to clamp (raise subdivisions)");
        fix(r);
      };
      switch (dof) {
        case SupportDof::Position:
          for (int c = 0; c < 3; ++c) fix_full(3 * end + c);
          break;
        case SupportDof::X:
          fix_full(3 * end);
          break;
        case SupportDof::Y:
          fix_full(3 * end + 1);
          break;
        case SupportDof::Z:
          fix_full(3 * end + 2);
          break;
        case SupportDof::Orientation:
          for (int c = 0; c < 3; ++c) {
            fix_full(3 * end + c);
            fix_full(3 * next + c);
          }
          fix_full(rod.theta_dof(edge));
          break;
        case SupportDof::OpeningAngle:
          throw ModelError("support at " + vertex_name(support.vertex) +
                           ": a free rod end has no opening angle to fix");
      }
    }
  }
  supports_ = supports;
  free_position_.assign(l.num_dofs(), -1);
  for (int i = 0; i < l.num_dofs(); ++i)
    if (!fixed_[i]) {
      free_position_[i] = static_cast<int>(free_.size());
      free_.push_back(i);
    }

  // Loads.
  point_forces_ = Eigen::VectorXd::Zero(l.num_dofs());
  for (int s = 0; s < l.num_segments(); ++s) {
    const ElasticRod& rod = l.segment(s);
    const Eigen::VectorXd mass = rod.lumped_mass();
    Eigen::VectorXd f = Eigen::VectorXd::Zero(rod.num_dofs());
    for (int n = 0; n < rod.num_nodes(); ++n) f.segment<3>(3 * n) = mass[3 * n] * setup.gravity;
    segment_forces_.push_back(f);
  }
  for (const PointLoad& load : setup.forces) {
    check_vertex(load.vertex, "a force");
    const int j = l.topology().joint_of_vertex[load.vertex];
    if (j >= 0) {
      point_forces_.segment<3>(l.joint_dof_offset(j) + kPosition) += load.force;
    } else {
      const RodLinkage::FreeEnd f = l.free_end(load.vertex);
      segment_forces_[f.segment].segment<3>(3 * f.end_node) += load.force;
    }
  }
  for (const Eigen::VectorXd& f : segment_forces_) has_segment_loads_.push_back(!f.isZero(0.0));
  has_point_loads_ = !point_forces_.isZero(0.0);
  // Point forces act on joint positions, which the input fixes: the
  // graph's vertices.
  input_dofs_ = Eigen::VectorXd::Zero(l.num_dofs());
  for (int j = 0; j < l.num_joints(); ++j)
    input_dofs_.segment<3>(l.joint_dof_offset(j) + kPosition) =
        l.graph().vertices[l.topology().joints[j].vertex];
}

Eigen::VectorXd LinkageProblem::free_dofs() const {
  const Eigen::VectorXd r = linkage_.dofs();
  Eigen::VectorXd q(free_.size());
  for (size_t i = 0; i < free_.size(); ++i) q[i] = r[free_[i]];
  return q;
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
  assembly_.hessian(linkage_, &segment_forces_, hessian_, &gradient_);
  gradient_ -= point_forces_;
  gradient_version_ = hessian_version_ = version_;
  return hessian_;
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
  Eigen::VectorXd v = Eigen::VectorXd::Zero(linkage_.num_dofs());
  for (size_t i = 0; i < free_.size(); ++i) v[free_[i]] = (*free_velocity)[i];
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
