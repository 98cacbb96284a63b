#include "graph_transform.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace xshell {

bool GraphTransform::is_identity() const {
  return mirror < 0 && scale == 1.0 && rotate_deg.isZero(0.0) && translate.isZero(0.0);
}

Eigen::Matrix3d GraphTransform::linear() const {
  Eigen::Matrix3d m = scale * Eigen::Matrix3d::Identity();
  if (mirror >= 0) m(mirror, mirror) = -scale;
  const Eigen::Vector3d rad = rotate_deg * (M_PI / 180.0);
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(rad.z(), Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(rad.y(), Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(rad.x(), Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  return rotation * m;
}

Eigen::Vector3d GraphTransform::apply(const Eigen::Vector3d& x) const {
  return linear() * x + translate;
}

LineGraph transformed(const LineGraph& graph, const GraphTransform& transform) {
  LineGraph out = graph;
  const Eigen::Matrix3d a = transform.linear();
  for (Eigen::Vector3d& v : out.vertices) v = a * v + transform.translate;
  return out;
}

}  // namespace xshell
