// An edge (or a chord) moved by a step de, turned rather than stretched
// (docs/model.md section 9.8): with t = e / |e|,
//   e' = (|e| + t . de) R(w) t,   w = t x de / |e| + twist t,
// R(w) the turn by the angle |w| about w: towards de_perp = de - (t . de) t
// by |de_perp| / |e|, and about the edge itself by `twist` (its material
// frame's turn on the same step, when known). To first order e' = e + de;
// an edge that turns rigidly with its frame, by R(w0) with w0 . t = twist,
// is turned by exactly R(w0).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace xshell {

inline Eigen::Vector3d turned_edge(const Eigen::Vector3d& e, const Eigen::Vector3d& de,
                                   double twist = 0.0) {
  const double length = e.norm();
  if (!(length > 0.0)) return e + de;
  const Eigen::Vector3d t = e / length;
  const double along = t.dot(de);
  const double new_length = length + along;
  // A step that shortens the edge to nothing or beyond: nothing to turn.
  if (!(new_length > 0.0)) return e + de;
  const Eigen::Vector3d w = t.cross(de) / length + twist * t;
  const double angle = w.norm();
  if (!(angle > 0.0)) return e + de;
  return new_length * (Eigen::AngleAxisd(angle, w / angle) * t);
}

}  // namespace xshell
