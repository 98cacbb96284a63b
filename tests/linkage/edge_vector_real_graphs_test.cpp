// What edge-vector joints make of the real linkage graphs of the reference
// implementation (../shared/data/elasticrods): joints whose rods are within
// kMinEdgeVectorAngleDegrees of parallel are refused at construction; the
// others build into the same linkage as with rotation joints.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "io/obj_reader.hpp"
#include "linkage/model_error.hpp"
#include "linkage/rod_linkage.hpp"
#include "skip.hpp"

namespace xshell::test {

TEST_CASE(
    "Real graphs with edge-vector joints: near-parallel joints are refused and the rest build" *
    doctest::test_suite("validation")) {
  const std::filesystem::path dir = XSHELL_SHARED_DATA_DIR;
  if (!std::filesystem::is_directory(dir)) XSHELL_SKIP(dir.string() + " is absent");
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  int graphs = 0, built = 0, refused = 0;
  for (const auto& path : files) {
    CAPTURE(path.filename().string());
    const LineGraph graph = read_obj(path.string());
    const LinkageTopology topology = build_topology(graph);
    // Angle of each joint's rods from parallel, in degrees.
    int below = 0, near = 0;
    double smallest = 90.0;
    for (const JointTopology& jt : topology.joints) {
      const double degrees = std::min(jt.opening_angle, M_PI - jt.opening_angle) * 180.0 / M_PI;
      smallest = std::min(smallest, degrees);
      below += degrees < kMinEdgeVectorAngleDegrees;
      near += degrees >= kMinEdgeVectorAngleDegrees && degrees < kCollinearDegrees;
    }
    LinkageOptions options;
    options.subdivisions = 8;
    options.material.young_modulus = 20000.0;
    options.material.section = {SectionShape::Rectangle, 10.0, 7.0};
    options.joint_kind = JointKind::EdgeVectors;
    bool ok = true;
    try {
      const RodLinkage linkage(graph, options);
      const double scale = linkage.segment(0).stiffness().stretching;
      CHECK(linkage.energy().total() <= 1e-16 * scale * graph.edges.size());
      CHECK(linkage.gradient().cwiseAbs().maxCoeff() <= 1e-9 * scale);
      ++built;
    } catch (const ModelError& e) {
      CHECK(std::string(e.what()).find("degrees from parallel") != std::string::npos);
      ok = false;
      ++refused;
    }
    CHECK(ok == (below == 0));
    MESSAGE(path.filename().string()
            << ": " << topology.joints.size() << " joints, " << below
            << " within 1 degree of parallel, " << near << " within 1-8 degrees, smallest "
            << smallest << " degrees: " << std::string(ok ? "builds" : "refused"));
    ++graphs;
  }
  CHECK(graphs == 10);
  CHECK(built + refused == graphs);
}

}  // namespace xshell::test
