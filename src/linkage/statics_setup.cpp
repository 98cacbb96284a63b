// Construction of a LinkageProblem from a StaticsSetup (statics_problem.hpp):
// the scales of the convergence measure, the supports (the default pin, the
// prescribed displacements, the unknowns they fix) and the dead loads.
#include <algorithm>
#include <string>
#include <vector>

#include "bounding_box.hpp"
#include "model_error.hpp"
#include "statics_problem.hpp"

namespace xshell {

namespace {

// "vertex v", for messages.
std::string vertex_name(int v) { return "vertex " + std::to_string(v); }

// Rejects a vertex index outside the linkage's nv vertices; what names the
// support or load that gave it.
void check_vertex(int v, int nv, const char* what) {
  if (v < 0 || v >= nv)
    throw ModelError(std::string(what) + " names " + vertex_name(v) + ", but the linkage has " +
                     std::to_string(nv) + " vertices");
}

// The total force per length of the line loads acting on full rod `rod`.
Eigen::Vector3d line_load_on(const std::vector<LineLoad>& loads, int rod) {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  for (const LineLoad& load : loads)
    if (load.rods.empty() || std::find(load.rods.begin(), load.rods.end(), rod) != load.rods.end())
      w += load.force_per_length;
  return w;
}

// EI_max: the largest bending stiffness of any segment.
double largest_bending_stiffness(const RodLinkage& l) {
  double bending_max = 0.0;
  for (int s = 0; s < l.num_segments(); ++s)
    bending_max = std::max(
        {bending_max, l.segment(s).stiffness().bending1, l.segment(s).stiffness().bending2});
  return bending_max;
}

// The vertex of the joint nearest centre (ties within 1e-12 length_scale:
// lowest index), pinned when no support is given.
int central_joint_vertex(const RodLinkage& l, const Eigen::Vector3d& centre, double length_scale) {
  if (l.num_joints() == 0)
    throw ModelError(
        "the linkage has no joint to pin by default: give supports that hold it in place");
  int best = -1;
  for (int j = 0; j < l.num_joints(); ++j) {
    const int v = l.topology().joints[j].vertex;
    if (best < 0 || (l.graph().vertices[v] - centre).norm() <
                        (l.graph().vertices[best] - centre).norm() - 1e-12 * length_scale)
      best = v;
  }
  return best;
}

// The position components a support holds.
struct HeldComponents {
  bool held[3] = {false, false, false};
};
HeldComponents held_components(const VertexSupport& support) {
  HeldComponents h;
  for (SupportDof dof : support.fix) {
    if (dof == SupportDof::Position) h.held[0] = h.held[1] = h.held[2] = true;
    if (dof == SupportDof::X) h.held[0] = true;
    if (dof == SupportDof::Y) h.held[1] = true;
    if (dof == SupportDof::Z) h.held[2] = true;
  }
  return h;
}

// Checks a support's vertex and displacement, and moves the position
// components it holds in `displaced` (reduced unknowns) to input +
// displacement (the input: the graph's vertex, or a free end's input nodes,
// both nodes of the end edge at a clamped end), whatever state the linkage
// is in (a restart from a saved state included), so that the supports are
// those of the configuration alone. Returns how far that moved the vertex
// (the joint's p or the free end's end node; held components only).
Eigen::Vector3d displace_support(const RodLinkage& l, const VertexSupport& support,
                                 Eigen::VectorXd& displaced) {
  check_vertex(support.vertex, static_cast<int>(l.graph().vertices.size()), "a support");
  if (!support.displacement.allFinite())
    throw ModelError("support at " + vertex_name(support.vertex) +
                     ": the displacement is not finite");
  const HeldComponents h = held_components(support);
  for (int c = 0; c < 3; ++c)
    if (support.displacement[c] != 0.0 && !h.held[c])
      throw ModelError("support at " + vertex_name(support.vertex) +
                       ": its displacement moves the " + std::string(1, char('x' + c)) +
                       " component, which the support does not hold (fix \"position\" or \"" +
                       std::string(1, char('x' + c)) + "\")");
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  const int j = l.topology().joint_of_vertex[support.vertex];
  if (j >= 0) {
    const int o = l.joint_dof_offset(j) + kPosition;
    for (int c = 0; c < 3; ++c)
      if (h.held[c]) {
        const double held = l.graph().vertices[support.vertex][c] + support.displacement[c];
        moved[c] = held - displaced[o + c];
        displaced[o + c] = held;
      }
    return moved;
  }
  const RodLinkage::FreeEnd f = l.free_end(support.vertex);
  const int s = f.segment, end = f.end_node, next = f.next_node;
  const Eigen::VectorXd& input = l.input_segment_dofs()[s];
  for (int node : {end, next}) {
    if (node == next && !f.clamped) continue;
    for (int c = 0; c < 3; ++c) {
      const int r = l.reduced_index(s, 3 * node + c);
      if (!h.held[c] || r < 0) continue;
      const double held = input[3 * node + c] + support.displacement[c];
      if (node == end) moved[c] = held - displaced[r];
      displaced[r] = held;
    }
  }
  return moved;
}

// Refuses supports that clamp other free ends than the linkage was built to
// clamp: a clamped end edge is centred on its vertex (docs/model.md section 8.2).
void check_clamps(const RodLinkage& l, const std::vector<VertexSupport>& supports) {
  const std::vector<int> wanted = clamped_free_ends(l.graph(), supports);
  const std::vector<int>& built = l.options().clamped_ends;
  for (int v : wanted)
    if (!std::binary_search(built.begin(), built.end(), v))
      throw ModelError("support at " + vertex_name(v) +
                       ": it clamps a free rod end that the linkage was built without a clamp "
                       "(build it with LinkageOptions::clamped_ends = clamped_free_ends(...))");
  for (int v : built)
    if (!std::binary_search(wanted.begin(), wanted.end(), v))
      throw ModelError("the linkage was built with a clamp at " + vertex_name(v) +
                       ", but no support fixes its \"orientation\"");
}

}  // namespace

std::vector<int> clamped_free_ends(const LineGraph& graph,
                                   const std::vector<VertexSupport>& supports) {
  const std::vector<int> valence = valences(graph);
  std::vector<int> out;
  for (const VertexSupport& support : supports) {
    const int v = support.vertex;
    if (v < 0 || v >= static_cast<int>(valence.size()) || valence[v] != 1) continue;
    if (std::find(support.fix.begin(), support.fix.end(), SupportDof::Orientation) !=
        support.fix.end())
      out.push_back(v);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

LinkageProblem::LinkageProblem(RodLinkage linkage, const StaticsSetup& setup)
    : linkage_(std::move(linkage)) {
  fixed_.assign(linkage_.num_dofs(), false);
  const BoundingBox box = bounding_box(linkage_.graph().vertices);
  length_scale_ = box.diagonal().norm();
  force_scale_ = largest_bending_stiffness(linkage_) / (length_scale_ * length_scale_);

  supports_ = setup.supports;
  if (supports_.empty()) {
    default_support_ = central_joint_vertex(linkage_, box.centre(), length_scale_);
    supports_.push_back({default_support_, {SupportDof::Position, SupportDof::Orientation}});
  }
  // The default pin holds its joint where the linkage is (it only removes
  // the rigid motions); the given supports hold input + displacement.
  Eigen::VectorXd displaced = linkage_.dofs();
  for (const VertexSupport& support : supports_)
    start_offsets_.push_back(default_support_ >= 0
                                 ? Eigen::Vector3d::Zero()
                                 : displace_support(linkage_, support, displaced));
  check_clamps(linkage_, supports_);
  linkage_.set_dofs(displaced);
  for (const VertexSupport& support : supports_) fix_support(support);
  free_position_.assign(linkage_.num_dofs(), -1);
  for (int i = 0; i < linkage_.num_dofs(); ++i)
    if (!fixed_[i]) {
      free_position_[i] = static_cast<int>(free_.size());
      free_.push_back(i);
    }
  set_loads(setup);
}

void LinkageProblem::fix_support(const VertexSupport& support) {
  const int j = linkage_.topology().joint_of_vertex[support.vertex];
  for (SupportDof dof : support.fix) {
    if (j >= 0)
      fix_at_joint(j, dof, support.vertex);
    else
      fix_at_free_end(support.vertex, dof);
  }
}

void LinkageProblem::fix_at_joint(int j, SupportDof dof, int vertex) {
  const RodLinkage& l = linkage_;
  const int o = l.joint_dof_offset(j);
  if (l.joint(j).kind() == JointKind::EdgeVectors && dof == SupportDof::Orientation) {
    // The constrained joint (docs/model.md section 8.1): directions fixed, lengths free.
    linkage_.align_joint(j);
    for (int base : {kEdgeA, kEdgeB})
      for (int c = 1; c < 3; ++c) fix(o + base + c);
    return;
  }
  if (l.joint(j).kind() == JointKind::EdgeVectors && dof == SupportDof::OpeningAngle)
    throw ModelError(
        "support at " + vertex_name(vertex) +
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
}

void LinkageProblem::fix_at_free_end(int vertex, SupportDof dof) {
  const RodLinkage& l = linkage_;
  const RodLinkage::FreeEnd f = l.free_end(vertex);
  const int s = f.segment, end = f.end_node, next = f.next_node, edge = f.edge;
  const ElasticRod& rod = l.segment(s);
  auto fix_full = [&](int full) {
    const int r = l.reduced_index(s, full);
    if (r < 0)
      throw ModelError("support at " + vertex_name(vertex) +
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
      throw ModelError("support at " + vertex_name(vertex) +
                       ": a free rod end has no opening angle to fix");
  }
}

void LinkageProblem::set_loads(const StaticsSetup& setup) {
  const RodLinkage& l = linkage_;
  point_forces_ = Eigen::VectorXd::Zero(l.num_dofs());
  const int num_rods = static_cast<int>(l.topology().rods.size());
  for (const LineLoad& load : setup.line_loads)
    for (int rod : load.rods)
      if (rod < 0 || rod >= num_rods)
        throw ModelError("a line load names rod " + std::to_string(rod) + ", but the linkage has " +
                         std::to_string(num_rods) + " rods");
  for (int s = 0; s < l.num_segments(); ++s) {
    const ElasticRod& rod = l.segment(s);
    const Eigen::VectorXd mass = rod.lumped_mass();
    Eigen::VectorXd f = Eigen::VectorXd::Zero(rod.num_dofs());
    for (int n = 0; n < rod.num_nodes(); ++n) f.segment<3>(3 * n) = mass[3 * n] * setup.gravity;
    const Eigen::Vector3d w = line_load_on(setup.line_loads, l.topology().segments[s].rod);
    if (!w.isZero(0.0)) {
      const Eigen::VectorXd length = rod.lumped_rest_lengths();
      for (int n = 0; n < rod.num_nodes(); ++n) f.segment<3>(3 * n) += length[n] * w;
    }
    segment_forces_.push_back(f);
  }
  for (const PointLoad& load : setup.forces) {
    check_vertex(load.vertex, static_cast<int>(l.graph().vertices.size()), "a force");
    const int j = l.topology().joint_of_vertex[load.vertex];
    if (j >= 0) {
      point_forces_.segment<3>(l.joint_dof_offset(j) + kPosition) += load.force;
    } else {
      const RodLinkage::FreeEnd f = l.free_end(load.vertex);
      Eigen::VectorXd& on_segment = segment_forces_[f.segment];
      if (f.clamped) {  // at the vertex, the clamped edge's midpoint
        on_segment.segment<3>(3 * f.end_node) += 0.5 * load.force;
        on_segment.segment<3>(3 * f.next_node) += 0.5 * load.force;
      } else {
        on_segment.segment<3>(3 * f.end_node) += load.force;
      }
    }
  }
  for (const Eigen::VectorXd& f : segment_forces_) has_segment_loads_.push_back(!f.isZero(0.0));
  has_point_loads_ = !point_forces_.isZero(0.0);
  rest_length_loads_ = !setup.gravity.isZero(0.0);
  for (const LineLoad& load : setup.line_loads)
    rest_length_loads_ = rest_length_loads_ || !load.force_per_length.isZero(0.0);
  given_segment_forces_ = segment_forces_;
  given_point_forces_ = point_forces_;
  // Point forces act on joint positions, which the input fixes: the
  // graph's vertices.
  input_dofs_ = Eigen::VectorXd::Zero(l.num_dofs());
  for (int j = 0; j < l.num_joints(); ++j)
    input_dofs_.segment<3>(l.joint_dof_offset(j) + kPosition) =
        l.graph().vertices[l.topology().joints[j].vertex];
}

}  // namespace xshell
