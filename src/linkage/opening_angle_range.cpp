#include "opening_angle_range.hpp"

#include <cmath>

namespace xshell {

OpeningAngleRange opening_angle_range(const std::vector<std::optional<double>>& angles) {
  OpeningAngleRange range;
  for (int v = 0; v < static_cast<int>(angles.size()); ++v) {
    if (!angles[v]) continue;
    const double a = *angles[v];
    if (!range.min || a < *range.min) {
      range.min = a;
      range.min_vertex = v;
    }
    if (!range.max || a > *range.max) {
      range.max = a;
      range.max_vertex = v;
    }
    // Not (0 < a < pi): a NaN is outside too.
    if (!(a > 0.0 && a < M_PI)) range.outside.push_back({v, a});
  }
  return range;
}

OpeningAngleRange opening_angle_range(const RodLinkage& linkage) {
  std::vector<std::optional<double>> angles(linkage.graph().vertices.size());
  for (int j = 0; j < linkage.num_joints(); ++j)
    angles[linkage.topology().joints[j].vertex] = linkage.joint(j).opening_angle();
  return opening_angle_range(angles);
}

}  // namespace xshell
