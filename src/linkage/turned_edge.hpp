// An edge (or a chord) moved by a step de, turned rather than stretched
// (docs/model.md section 9.8): with t = e / |e|,
//   e' = (|e| + t . de) (cos phi t + sin phi n),   phi = |de_perp| / |e|,
// n the unit de_perp = de - (t . de) t. To first order e' = e + de.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace xshell {

inline Eigen::Vector3d turned_edge(const Eigen::Vector3d& e, const Eigen::Vector3d& de) {
  const double length = e.norm();
  if (!(length > 0.0)) return e + de;
  const Eigen::Vector3d t = e / length;
  const double along = t.dot(de);
  const Eigen::Vector3d across = de - along * t;
  const double new_length = length + along;
  const double across_norm = across.norm();
  // A step that shortens the edge to nothing or beyond: nothing to turn.
  if (!(new_length > 0.0) || !(across_norm > 0.0)) return e + de;
  const double angle = across_norm / length;
  return new_length * (std::cos(angle) * t + std::sin(angle) * (across / across_norm));
}

}  // namespace xshell
