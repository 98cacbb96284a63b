// Per-rod sections (LinkageOptions::segment_materials) reach the snapshot,
// so the solids show each rod's own section.
#include <doctest/doctest.h>

#include "io/vtk/linkage_snapshot.hpp"
#include "linkage/linkage_fixtures.hpp"

namespace xshell::test {

TEST_CASE("linkage snapshot: each rod carries the section of its own segments") {
  const LineGraph graph = single_x();  // two rods crossing at vertex 0
  LinkageOptions o = test_options();
  const LinkageTopology topology = build_topology(graph);
  REQUIRE(topology.rods.size() == 2);
  for (const SegmentTopology& seg : topology.segments) {
    Material m = o.material;
    m.section = seg.rod == 0 ? CrossSection{SectionShape::Ellipse, 0.11, 0.04}
                             : CrossSection{SectionShape::Rectangle, 0.06, 0.09};
    o.segment_materials.push_back(m);
  }
  const Snapshot snap = linkage_snapshot(RodLinkage(graph, o), Eigen::Vector3d::Zero(), 0.0);
  REQUIRE(snap.rods.size() == 2);
  int checked = 0;
  for (const RodSnapshot& rod : snap.rods) {
    CAPTURE(rod.rod_id);
    const bool first = rod.rod_id == 0;
    CHECK(rod.section.shape ==
          (first ? SectionSnapshot::Shape::Ellipse : SectionSnapshot::Shape::Rectangle));
    CHECK(rod.section.width == (first ? 0.11 : 0.06));
    CHECK(rod.section.height == (first ? 0.04 : 0.09));
    ++checked;
  }
  CHECK(checked == 2);
}

}  // namespace xshell::test
