#include "edge_rotation_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "turned_edge.hpp"

namespace xshell {

namespace {

// The largest angle (radians) by which a step along the path may turn an
// edge or its material frame: beyond a quarter turn no Newton step means
// anything, and a mechanism whose energy barely changes (a rod swinging
// free about its joint) would be spun round and round by the expansion.
constexpr double kLargestTurn = 0.5 * M_PI;

// Spreads the gap left at the end of a run (its nodes first..last, placed
// by summing edges from node first - 1) along it in proportion to arc length.
void close_gap(int first, int last, const Eigen::Vector3d& gap, std::vector<Eigen::Vector3d>& nodes,
               const Eigen::Vector3d& far_end) {
  double total = (far_end - nodes[last]).norm();
  for (int i = first; i <= last; ++i) total += (nodes[i] - nodes[i - 1]).norm();
  if (!(total > 0.0)) return;
  double run = 0.0;
  Eigen::Vector3d previous = nodes[first - 1];
  for (int i = first; i <= last; ++i) {
    run += (nodes[i] - previous).norm();
    previous = nodes[i];
    nodes[i] += (run / total) * gap;
  }
}

}  // namespace

EdgeRotationPath::EdgeRotationPath(const LinkageProblem& problem) : joints_(problem) {
  const RodLinkage& linkage = problem.linkage();
  node_unknowns_.resize(linkage.num_segments());
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const int nodes = linkage.segment(s).num_nodes();
    node_unknowns_[s].assign(nodes, Eigen::Vector3i::Constant(-1));
    for (int i = 0; i < nodes; ++i) {
      Eigen::Vector3i unknowns;
      for (int c = 0; c < 3; ++c) {
        const int reduced = linkage.reduced_index(s, 3 * i + c);
        unknowns[c] = reduced >= 0 ? problem.free_position(reduced) : -1;
      }
      if ((unknowns.array() >= 0).all()) node_unknowns_[s][i] = unknowns;
    }
  }
}

void EdgeRotationPath::start(const LinkageProblem& problem, const Eigen::VectorXd& p,
                             bool place_joints) {
  q0_ = problem.free_dofs();
  p_ = p;
  place_joints_ = place_joints && joints_.active();
  const RodLinkage& linkage = problem.linkage();
  start_nodes_.resize(linkage.num_segments());
  for (int s = 0; s < linkage.num_segments(); ++s) start_nodes_[s] = linkage.segment(s).nodes();
  start_velocities(problem);
  if (place_joints_) joints_.start(problem);
}

void EdgeRotationPath::start_velocities(const LinkageProblem& problem) {
  const RodLinkage& linkage = problem.linkage();
  const Eigen::VectorXd reduced = problem.with_fixed_zero(p_);
  start_velocities_.resize(linkage.num_segments());
  twist_rates_.resize(linkage.num_segments());
  double fastest = 0.0;  // the largest rate at which an edge turns (radians per unit alpha)
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const ElasticRod& rod = linkage.segment(s);
    const Eigen::VectorXd v = linkage.full_velocity(s, reduced);
    start_velocities_[s].resize(rod.num_nodes());
    for (int i = 0; i < rod.num_nodes(); ++i)
      start_velocities_[s][i] = v.segment<3>(ElasticRod::node_dof(i));
    twist_rates_[s].resize(rod.num_edges());
    for (int j = 0; j < rod.num_edges(); ++j) {
      twist_rates_[s][j] = v[rod.theta_dof(j)];
      const Eigen::Vector3d e = start_nodes_[s][j + 1] - start_nodes_[s][j];
      const Eigen::Vector3d de = start_velocities_[s][j + 1] - start_velocities_[s][j];
      const double turn = e.cross(de).norm() / e.squaredNorm();
      fastest = std::max({fastest, turn, std::abs(twist_rates_[s][j])});
    }
  }
  longest_ = fastest > 0.0 ? kLargestTurn / fastest : std::numeric_limits<double>::infinity();
}

Eigen::VectorXd EdgeRotationPath::point(const LinkageProblem& problem, double alpha) const {
  if (alpha > longest_)
    throw std::domain_error("the step turns an edge by more than a quarter turn");
  Eigen::VectorXd q = q0_ + alpha * p_;
  // Beyond the full step (the expansion) the joints take the straight step.
  if (place_joints_ && alpha <= 1.0) joints_.place(q);
  const std::vector<std::vector<Eigen::Vector3d>> placed = problem.nodes_at(q);
  std::vector<Eigen::Vector3d> nodes;
  for (int s = 0; s < problem.linkage().num_segments(); ++s) {
    turn_segment(s, alpha, placed[static_cast<size_t>(s)], nodes);
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
      const Eigen::Vector3i& unknowns = node_unknowns_[s][i];
      if (unknowns[0] >= 0)
        for (int c = 0; c < 3; ++c) q[unknowns[c]] = nodes[i][c];
    }
  }
  return q;
}

void EdgeRotationPath::turn_segment(int s, double alpha, const std::vector<Eigen::Vector3d>& placed,
                                    std::vector<Eigen::Vector3d>& nodes) const {
  const std::vector<Eigen::Vector3d>& start = start_nodes_[s];
  const std::vector<Eigen::Vector3d>& velocity = start_velocities_[s];
  const std::vector<Eigen::Vector3i>& unknowns = node_unknowns_[s];
  const int n = static_cast<int>(placed.size());
  nodes = placed;
  auto is_free = [&](int i) { return unknowns[i][0] >= 0; };
  // Where the straight step puts node i to first order: a free node on the
  // line; a node that the joints or supports place, by its velocity at
  // alpha = 0 (a joint turns its terminal nodes on arcs, whose second-order
  // part would otherwise lengthen or shorten the free edge next to them).
  auto straight = [&](int i) -> Eigen::Vector3d {
    if (is_free(i)) return placed[i];
    return start[i] + alpha * velocity[i];
  };
  // Edge i -> i + 1 after the step.
  auto edge = [&](int i) {
    return turned_edge(start[i + 1] - start[i],
                       (straight(i + 1) - straight(i)) - (start[i + 1] - start[i]),
                       alpha * twist_rates_[s][i]);
  };
  for (int a = 0; a < n; ++a) {
    if (!is_free(a)) continue;
    int b = a;
    while (b + 1 < n && is_free(b + 1)) ++b;
    const bool left = a > 0, right = b + 1 < n;
    if (right && !left) {  // summed back from the node after the run
      for (int i = b; i >= a; --i) nodes[i] = nodes[i + 1] - edge(i);
    } else {
      // From the node before the run; with none (no node of the segment is
      // placed), from the first node where the straight step puts it.
      const int first = left ? a : a + 1;
      for (int i = first; i <= b; ++i) nodes[i] = nodes[i - 1] + edge(i - 1);
      if (right && first <= b)
        close_gap(first, b, placed[b + 1] - (nodes[b] + edge(b)), nodes, placed[b + 1]);
    }
    a = b;
  }
}

}  // namespace xshell
