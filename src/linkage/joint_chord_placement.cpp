#include "joint_chord_placement.hpp"

#include <Eigen/SparseCore>

#include "turned_edge.hpp"

namespace xshell {

JointChordPlacement::JointChordPlacement(const LinkageProblem& problem) {
  const RodLinkage& linkage = problem.linkage();
  const LinkageTopology& topology = linkage.topology();
  // Points: every joint, then the free ends that the supports hold.
  std::vector<int> point_of_vertex(topology.valence.size(), -1);
  for (int j = 0; j < linkage.num_joints(); ++j) {
    Point point;
    point.vertex = topology.joints[j].vertex;
    for (int c = 0; c < 3; ++c)
      point.unknowns[c] = problem.free_position(linkage.joint_dof_offset(j) + c);
    if ((point.unknowns.array() >= 0).all()) {
      point.free_joint = static_cast<int>(free_joints_.size());
      free_joints_.push_back(static_cast<int>(points_.size()));
    }
    point_of_vertex[point.vertex] = static_cast<int>(points_.size());
    points_.push_back(point);
  }
  auto end_point = [&](int s, int side) {
    const int vertex = topology.segments[s].vertex[side];
    if (point_of_vertex[vertex] >= 0) return point_of_vertex[vertex];
    const RodLinkage::FreeEnd end = linkage.free_end(vertex);
    for (int c = 0; c < 3; ++c) {
      const int r = linkage.reduced_index(s, 3 * end.end_node + c);
      if (r >= 0 && problem.free_position(r) >= 0) return -1;  // the end moves: no chord
    }
    Point point;
    point.vertex = vertex;
    point.unknowns.setConstant(-1);
    point_of_vertex[vertex] = static_cast<int>(points_.size());
    points_.push_back(point);
    return point_of_vertex[vertex];
  };
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const int from = end_point(s, 0), to = end_point(s, 1);
    if (from < 0 || to < 0) continue;
    if (points_[from].free_joint < 0 && points_[to].free_joint < 0) continue;
    const double length = topology.segments[s].length;
    chords_.push_back({from, to, length > 0.0 ? 1.0 / length : 1.0});
  }
  if (!active()) return;
  factorize_normal_matrix();
}

void JointChordPlacement::factorize_normal_matrix() {
  double total_weight = 0.0;
  for (const Chord& chord : chords_) total_weight += chord.weight;
  pull_ = kStraightPull * total_weight / static_cast<double>(chords_.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < static_cast<int>(free_joints_.size()); ++k) entries.emplace_back(k, k, pull_);
  for (const Chord& chord : chords_) {
    const int a = points_[chord.from].free_joint, b = points_[chord.to].free_joint;
    if (a >= 0) entries.emplace_back(a, a, chord.weight);
    if (b >= 0) entries.emplace_back(b, b, chord.weight);
    if (a >= 0 && b >= 0) {
      entries.emplace_back(a, b, -chord.weight);
      entries.emplace_back(b, a, -chord.weight);
    }
  }
  const int n = static_cast<int>(free_joints_.size());
  Eigen::SparseMatrix<double> normal(n, n);
  normal.setFromTriplets(entries.begin(), entries.end());
  normal_matrix_.compute(normal);
}

void JointChordPlacement::start(const LinkageProblem& problem) {
  for (Point& point : points_) point.start = problem.linkage().vertex_position(point.vertex);
}

Eigen::Vector3d JointChordPlacement::straight(const Point& point, const Eigen::VectorXd& q) const {
  Eigen::Vector3d x = point.start;
  for (int c = 0; c < 3; ++c)
    if (point.unknowns[c] >= 0) x[c] = q[point.unknowns[c]];
  return x;
}

void JointChordPlacement::place(Eigen::VectorXd& q) const {
  if (!active()) return;
  std::vector<Eigen::Vector3d> line(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) line[i] = straight(points_[i], q);
  const int n = static_cast<int>(free_joints_.size());
  Eigen::MatrixXd rhs(n, 3);
  for (int k = 0; k < n; ++k) rhs.row(k) = pull_ * line[free_joints_[k]].transpose();
  for (const Chord& chord : chords_) {
    const Point &from = points_[chord.from], &to = points_[chord.to];
    const Eigen::Vector3d &x_from = line[chord.from], &x_to = line[chord.to];
    const Eigen::Vector3d c0 = to.start - from.start;
    const Eigen::Vector3d c = turned_edge(c0, (x_to - x_from) - c0);
    const double w = chord.weight;
    if (from.free_joint >= 0)
      rhs.row(from.free_joint) -=
          w * (to.free_joint >= 0 ? c : Eigen::Vector3d(c - x_to)).transpose();
    if (to.free_joint >= 0)
      rhs.row(to.free_joint) +=
          w * (from.free_joint >= 0 ? c : Eigen::Vector3d(c + x_from)).transpose();
  }
  const Eigen::MatrixXd x = normal_matrix_.solve(rhs);
  for (int k = 0; k < n; ++k) {
    const int i = free_joints_[k];
    for (int c = 0; c < 3; ++c) q[points_[i].unknowns[c]] = x(k, c);
  }
}

}  // namespace xshell
