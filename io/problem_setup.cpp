#include "problem_setup.hpp"

namespace xshell {

namespace {
SupportDof to_support(Fixed f) {
  switch (f) {
    case Fixed::Position: return SupportDof::Position;
    case Fixed::X: return SupportDof::X;
    case Fixed::Y: return SupportDof::Y;
    case Fixed::Z: return SupportDof::Z;
    case Fixed::Orientation: return SupportDof::Orientation;
    case Fixed::OpeningAngle: return SupportDof::OpeningAngle;
  }
  return SupportDof::Position;
}
}  // namespace

ProblemSetup make_problem_setup(const Config& config, const LineGraph& graph) {
  check_vertices(config, graph);
  ProblemSetup setup;
  Eigen::Vector3d lo = graph.vertices.at(0), hi = lo;
  for (const auto& v : graph.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  setup.origin = 0.5 * (lo + hi);
  setup.graph = graph;
  for (auto& v : setup.graph.vertices) v -= setup.origin;

  setup.options.subdivisions = config.subdivisions;
  setup.options.rest_shape = config.rest_shape;
  setup.options.joint_kind =
      config.joints == JointModel::EdgeVectors ? JointKind::EdgeVectors : JointKind::Rotation;
  setup.options.material.young_modulus = config.material.young_modulus;
  setup.options.material.poisson_ratio = config.material.poisson_ratio;
  setup.options.material.density = config.material.density;
  setup.options.material.section = {config.material.cross_section.shape, config.material.cross_section.width,
                                    config.material.cross_section.height};

  for (const Support& s : config.supports) {
    VertexSupport vs{s.vertex, {}};
    for (Fixed f : s.fix) vs.fix.push_back(to_support(f));
    setup.statics.supports.push_back(vs);
  }
  setup.statics.gravity = config.loads.gravity;
  for (const PointForce& f : config.loads.forces) setup.statics.forces.push_back({f.vertex, f.force});
  return setup;
}

}  // namespace xshell
