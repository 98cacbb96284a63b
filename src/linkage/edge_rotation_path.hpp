// The curve that the Newton line searches follow on a linkage
// (docs/model.md section 9.8): from q0 along a step p, the free nodes move by
// turning each edge rather than along straight lines.
//
// A straight step q0 + alpha p moves a rod's free nodes on straight lines: a
// rigid turn of an edge by an angle phi then stretches it by (sec phi - 1),
// and with the stiff stretching of a slender rod the energy forbids all but
// small turns (large deflections, mechanisms swinging: hundreds of short
// Newton steps). The path here keeps everything the straight step sets except
// the free node positions: each edge e with step de (from the straight step
// at the same alpha) becomes
//   e' = (|e| + t . de) R(t x de / |e|) t,     t = e / |e|,
// the turn R by the angle |de_perp| / |e| towards de_perp, and the free nodes
// follow by summing the new edges from a node that the straight step places
// (a joint's node, a held one); between two such nodes the gap left at the
// far one is spread along the run in proportion to arc length. On the step
// of an unshifted Newton system (place_joints) and up to the full step, the
// joints' positions turn too, with the chords between them
// (joint_chord_placement.hpp). Everything else (the joints' rotations and
// angles, thetas) takes the straight step. To first order e' = e + de: the
// path leaves q0 with tangent p, so a line search along it finds an energy
// decrease wherever the straight one does, and a rigid turn of a run of
// edges is exact.
#pragma once

#include <Eigen/Core>
#include <array>
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
  // The free unknowns at alpha along the path. Moves the problem (to
  // q0 + alpha p with the joints placed); throws std::domain_error where
  // that is not a valid configuration.
  Eigen::VectorXd point(LinkageProblem& problem, double alpha) const;

 private:
  // The positions of segment s's nodes along the path, from their start
  // (start_nodes_) and their positions on the straight step with the joints
  // placed (`placed`; the joints at its ends moved by joint_shift from the
  // straight step): the free runs start from the placed joints' nodes and
  // turn their edges by the straight step's.
  void turn_segment(int s, const std::vector<Eigen::Vector3d>& placed,
                    const std::array<Eigen::Vector3d, 2>& joint_shift,
                    std::vector<Eigen::Vector3d>& nodes) const;

  // Per segment and node: the free unknown of each coordinate (x, y, z), or
  // -1 for a node that the straight step places (a joint's, a held one).
  std::vector<std::vector<Eigen::Vector3i>> node_unknowns_;
  JointChordPlacement joints_;
  bool place_joints_ = false;
  Eigen::VectorXd q0_, p_;
  std::vector<std::vector<Eigen::Vector3d>> start_nodes_;
};

}  // namespace xshell
