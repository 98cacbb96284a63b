// The curve that the Newton line searches follow on a linkage
// (docs/model.md section 9.8): from q0 along a step p, the free nodes move by
// turning each edge rather than along straight lines.
//
// A straight step q0 + alpha p moves a rod's free nodes on straight lines: a
// rigid turn of an edge by an angle phi then stretches it by (sec phi - 1),
// and with the stiff stretching of a slender rod the energy forbids all but
// small turns (large deflections, mechanisms swinging: hundreds of short
// Newton steps). The path here keeps everything the straight step sets except
// the free node positions: each edge e with step de (the straight step at
// the same alpha, to first order) and theta step dtheta becomes
//   e' = (|e| + t . de) R(t x de / |e| + dtheta t) t,     t = e / |e|
// (turned_edge.hpp), and the free nodes follow by summing the new edges from
// a node that the straight step places (a joint's node, a held one); between
// two such nodes the gap left at the far one is spread along the run in
// proportion to arc length. The straight step of a node that a joint places
// is its velocity at q0 times alpha, not the point on the joint's arc: the
// free edge next to it would stretch by the arc's second-order part. On the
// step of an unshifted Newton system (place_joints) and up to the full step,
// the joints' positions turn too, with the chords between them
// (joint_chord_placement.hpp). Everything else (the joints' rotations and
// angles, thetas) takes the straight step. To first order e' = e + de: the
// path leaves q0 with tangent p, so a line search along it finds an energy
// decrease wherever the straight one does, and a rigid turn of a run of
// edges with its frames is exact. The path ends where an edge or its frame
// has turned by a quarter turn.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "joint_chord_placement.hpp"
#include "statics_problem.hpp"

namespace xshell {

class EdgeRotationPath {
 public:
  explicit EdgeRotationPath(const LinkageProblem& problem);

  // Starts a path at the problem's current configuration q0 (free unknowns)
  // along the free step p; with place_joints the joints' positions follow
  // their turned chords up to alpha = 1 (docs/model.md section 9.8 says when).
  void start(const LinkageProblem& problem, const Eigen::VectorXd& p, bool place_joints = false);
  // The free unknowns at alpha along the path (the problem stays where it
  // is); throws std::domain_error where q0 + alpha p with the joints placed
  // is not a valid configuration, or where an edge or its frame would turn
  // by more than a quarter turn from q0.
  Eigen::VectorXd point(const LinkageProblem& problem, double alpha) const;

 private:
  // The positions of segment s's nodes at alpha along the path, from their
  // start (start_nodes_) and their positions on the straight step with the
  // joints placed (`placed`): the free runs start from the placed nodes and
  // turn their edges by the first-order straight step's.
  void turn_segment(int s, double alpha, const std::vector<Eigen::Vector3d>& placed,
                    std::vector<Eigen::Vector3d>& nodes) const;
  // start_velocities_, twist_rates_ and longest_ at q0 along p.
  void start_velocities(const LinkageProblem& problem);

  // Per segment and node: the free unknown of each coordinate (x, y, z), or
  // -1 for a node that the straight step places (a joint's, a held one).
  std::vector<std::vector<Eigen::Vector3i>> node_unknowns_;
  JointChordPlacement joints_;
  bool place_joints_ = false;
  Eigen::VectorXd q0_, p_;
  // Per segment: the nodes at q0, their velocities d/dalpha there, and each
  // edge's d(theta)/d(alpha).
  std::vector<std::vector<Eigen::Vector3d>> start_nodes_, start_velocities_;
  std::vector<std::vector<double>> twist_rates_;
  double longest_ = 0.0;  // the largest alpha: no edge turns by more than a quarter turn
};

}  // namespace xshell
