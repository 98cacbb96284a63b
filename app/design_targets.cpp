#include "design_targets.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/target_joints_file.hpp"

namespace xshell {

namespace {

DesignTargets joint_targets(const Config& config, const RodLinkage& linkage,
                            const Eigen::Vector3d& origin) {
  const int n = static_cast<int>(linkage.graph().vertices.size());
  const TargetJoints file = read_target_joints(config.design->target_joints, n);
  DesignTargets out;
  for (int v = 0; v < n; ++v)
    if (file.positions[v])
      out.targets.push_back({v, config.transform.apply(*file.positions[v]) - origin, 1.0});
  return out;
}

DesignTargets surface_targets(const Config& config, const RodLinkage& linkage,
                              const Eigen::Vector3d& origin) {
  const std::string& path = config.design->target_surface;
  ObjSurface surface = read_obj_surface(path);
  for (Eigen::Vector3d& x : surface.vertices) x = config.transform.apply(x) - origin;
  DesignTargets out;
  try {
    out.surface =
        std::make_shared<const TriangleTree>(std::move(surface.vertices), surface.triangles);
  } catch (const std::invalid_argument& e) {
    throw InputError(printable(path) + ": " + e.what());
  }
  const std::vector<int>& joint_of_vertex = linkage.topology().joint_of_vertex;
  for (int v = 0; v < static_cast<int>(joint_of_vertex.size()); ++v)
    if (joint_of_vertex[v] >= 0) out.targets.push_back({v, Eigen::Vector3d::Zero(), 1.0});
  std::shared_ptr<const TriangleTree> tree = out.surface;
  out.retarget = [tree](const RodLinkage& deployed, std::vector<VertexTarget>& targets) {
    for (VertexTarget& t : targets)
      t.position = tree->closest(deployed.vertex_position(t.vertex)).point;
  };
  out.retarget(linkage, out.targets);
  return out;
}

}  // namespace

DesignTargets read_design_targets(const Config& config, const RodLinkage& linkage,
                                  const Eigen::Vector3d& origin) {
  if (!config.design) throw std::logic_error("read_design_targets: no design section");
  return config.design->target_surface.empty() ? joint_targets(config, linkage, origin)
                                               : surface_targets(config, linkage, origin);
}

std::vector<double> target_distances(const RodLinkage& linkage,
                                     const std::vector<VertexTarget>& targets) {
  std::vector<double> d(linkage.graph().vertices.size(), std::numeric_limits<double>::quiet_NaN());
  for (const VertexTarget& t : targets)
    d[t.vertex] = (linkage.vertex_position(t.vertex) - t.position).norm();
  return d;
}

}  // namespace xshell
