// Where the edge-turning path (edge_rotation_path.hpp, docs/model.md
// section 9.8) puts the joints: a straight step moves a joint's position on
// a line, so a mechanism whose joints swing about one another (a four-bar
// loop shearing, a lath turning about its joint) stretches the segments
// between them by (sec phi - 1). Here each segment's chord (joint to joint,
// or joint to a free end whose end node the supports hold) is turned as the
// path turns an edge, by the angle of its straight step, and the free
// joints' positions are the least squares fit of the turned chords (weighted
// by 1/length, the chord's stretching stiffness), the joints whose position
// the supports hold (in part or whole) and the held ends fixed where the
// straight step puts them. A small pull
// (kStraightPull) towards the straight positions fixes the translation of a
// part that nothing holds. Turned chords that close every loop (a
// parallelogram shearing, any tree) are matched exactly; and since a turned
// chord is its straight step to first order, the fit is the straight step to
// first order (the path keeps its tangent).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <vector>

#include "statics_problem.hpp"

namespace xshell {

class JointChordPlacement {
 public:
  static constexpr double kStraightPull = 1e-6;

  explicit JointChordPlacement(const LinkageProblem& problem);

  // True when there is a joint to place (a free joint position and a chord).
  bool active() const { return !free_joints_.empty() && !chords_.empty(); }
  // Records the joints' and held ends' positions at the start q0.
  void start(const LinkageProblem& problem);
  // Replaces the free joints' positions in q (free unknowns on the straight
  // step from q0) by the fit of the turned chords.
  void place(Eigen::VectorXd& q) const;

 private:
  struct Point {
    int vertex = -1;           // graph vertex
    int free_joint = -1;       // index in free_joints_, or -1 for a fixed point
    Eigen::Vector3i unknowns;  // free unknowns of x, y, z (-1: held)
    Eigen::Vector3d start;     // position at q0
  };
  struct Chord {
    int from = -1, to = -1;  // indices in points_
    double weight = 1.0;
  };

  // A point's position on the straight step (q: free unknowns).
  Eigen::Vector3d straight(const Point& point, const Eigen::VectorXd& q) const;
  // The fit's normal equations (the same for every coordinate).
  void factorize_normal_matrix();

  std::vector<Point> points_;     // the joints (in order), then the held ends
  std::vector<int> free_joints_;  // points_ index of each free joint
  std::vector<Chord> chords_;
  double pull_ = 0.0;  // weight of the pull towards the straight positions
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> normal_matrix_;
};

}  // namespace xshell
