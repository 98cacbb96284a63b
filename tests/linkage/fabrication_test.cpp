// Fabrication data (linkage/fabrication.hpp): cut lengths and stations
// against the drawing of straight grids, and the invariants every linkage
// must satisfy (stations increasing from 0 to the length, every joint on
// exactly two rods, valence 2 and 3 joints, closed rods, families).
#include "linkage/fabrication.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <map>

#include "io/obj_reader.hpp"
#include "linkage_fixtures.hpp"
#include "skip.hpp"

namespace xshell::test {

namespace {

// A regular octagon (radius 1) whose vertices each carry a radial spoke to a
// free end: the octagon is one closed rod through eight valence-3 joints,
// each spoke a rod that ends at one of them.
LineGraph ring_with_spokes() {
  LineGraph g;
  for (int k = 0; k < 8; ++k) {
    const double a = k * M_PI / 4.0;
    g.vertices.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  for (int k = 0; k < 8; ++k) {
    const double a = k * M_PI / 4.0;
    g.vertices.emplace_back(1.6 * std::cos(a), 1.6 * std::sin(a), 0.0);
  }
  for (int k = 0; k < 8; ++k) g.edges.push_back({k, (k + 1) % 8});
  for (int k = 0; k < 8; ++k) g.edges.push_back({k, 8 + k});
  return g;
}

// A straight beam: one rod, no joints.
LineGraph beam() {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {1, 0, 0}};
  g.edges = {{0, 1}};
  return g;
}

// The graph vertices along rod r in rod order (both ends included).
std::vector<int> rod_vertices(const LinkageTopology& topo, int r) {
  std::vector<int> out;
  const RodChain& chain = topo.rods[r];
  for (size_t k = 0; k < chain.segments.size(); ++k) {
    const auto& v = topo.segments[chain.segments[k]].vertex;
    const int a = chain.forward[k] ? v[0] : v[1], b = chain.forward[k] ? v[1] : v[0];
    if (out.empty()) out.push_back(a);
    out.push_back(b);
  }
  return out;
}

// The invariants of the header, on any linkage; returns how many stations
// were checked.
int check_invariants(const RodLinkage& linkage, const FabricationData& data) {
  const LinkageTopology& topo = linkage.topology();
  REQUIRE(data.rods.size() == topo.rods.size());
  REQUIRE(static_cast<int>(data.joints.size()) == linkage.num_joints());
  int checked = 0;
  std::map<int, std::vector<std::pair<int, double>>> on_rods;  // joint -> (rod, s)
  for (size_t r = 0; r < data.rods.size(); ++r) {
    const FabricationRod& rod = data.rods[r];
    CAPTURE(r);
    CHECK(rod.rod == static_cast<int>(r));
    REQUIRE(rod.stations.size() >= 2);
    CHECK(rod.stations.front().kind == StationKind::End);
    CHECK(rod.stations.back().kind == StationKind::End);
    CHECK(rod.stations.front().s == 0.0);
    CHECK(rod.stations.back().s == rod.length);
    CHECK(rod.length > 0.0);
    for (size_t k = 1; k < rod.stations.size(); ++k) {
      CHECK(rod.stations[k].s > rod.stations[k - 1].s);
      ++checked;
    }
    for (size_t k = 1; k + 1 < rod.stations.size(); ++k) {
      const RodStation& st = rod.stations[k];
      CHECK(st.kind == StationKind::Joint);
      REQUIRE(st.joint >= 0);
      CHECK(st.vertex == topo.joints[st.joint].vertex);
      on_rods[st.joint].push_back({rod.rod, st.s});
    }
    // The cut length: every segment's rest lengths, each terminal edge
    // shared by two segments of the rod (a joint it passes through) once.
    double sum = 0.0;
    for (int seg : topo.rods[r].segments)
      for (double l : linkage.segment(seg).rest_lengths()) sum += l;
    for (const JointTopology& jt : topo.joints)
      for (int x = 0; x < 2; ++x)
        if (jt.rod[x] == static_cast<int>(r) && jt.ends[x].size() == 2) {
          const SegmentEnd& end = jt.ends[x][0];
          const std::vector<double>& rest = linkage.segment(end.segment).rest_lengths();
          sum -= end.at_start ? rest.front() : rest.back();
        }
    CHECK(rod.length == doctest::Approx(sum).epsilon(1e-13));
    // The cross-section is the rod's material's.
    CHECK(rod.section.width == linkage.segment_material(topo.rods[r].segments[0]).section.width);
  }
  // Every joint is a station of exactly its two rods, once each, at the s
  // its own record gives.
  for (const FabricationJoint& joint : data.joints) {
    CAPTURE(joint.vertex);
    const auto& found = on_rods[joint.joint];
    REQUIRE(found.size() == 2);
    CHECK(found[0].first != found[1].first);
    for (int x = 0; x < 2; ++x) {
      const auto it = std::find_if(found.begin(), found.end(),
                                   [&](const auto& p) { return p.first == joint.rod[x]; });
      REQUIRE(it != found.end());
      CHECK(it->second == joint.s[x]);
    }
    CHECK(joint.rod == topo.joints[joint.joint].rod);
    CHECK(joint.valence == topo.valence[joint.vertex]);
    CHECK(joint.angle_input == topo.joints[joint.joint].opening_angle);
    CHECK(joint.angle == linkage.joint(joint.joint).opening_angle());
    ++checked;
  }
  return checked;
}

}  // namespace

TEST_CASE("Fabrication: the sample grid's stations are its drawing's vertex spacing") {
  const LineGraph graph =
      read_obj((std::filesystem::path(XSHELL_SAMPLES_DIR) / "grid.obj").string());
  int checked = 0;
  for (RestShape rest : {RestShape::Straight, RestShape::Input}) {
    const RodLinkage linkage(graph, test_options(rest, 8));
    const FabricationData data = fabrication_data(linkage);
    checked += check_invariants(linkage, data);
    REQUIRE(data.rods.size() == 8);
    for (const FabricationRod& rod : data.rods) {
      CAPTURE(rod.rod);
      // Free ends at both ends: the stations are the rod's vertices, at
      // their distances along the drawn polyline.
      const std::vector<int> vertices = rod_vertices(linkage.topology(), rod.rod);
      REQUIRE(rod.stations.size() == vertices.size());
      double s = 0.0;
      for (size_t k = 0; k < vertices.size(); ++k) {
        if (k > 0) s += (graph.vertices[vertices[k]] - graph.vertices[vertices[k - 1]]).norm();
        CHECK(rod.stations[k].vertex == vertices[k]);
        CHECK(rod.stations[k].s == doctest::Approx(s).epsilon(1e-13));
        ++checked;
      }
      CHECK(rod.length == doctest::Approx(1.0).epsilon(1e-13));  // the grid's rods: 1 m
      CHECK(rod.other_label_vertices.empty());
    }
    // 4 x 4 crossings, in the interior of both rods: 0.125 + 0.25 k.
    for (const FabricationJoint& joint : data.joints)
      for (double s : joint.s) {
        const double k = (s - 0.125) / 0.25;
        CHECK(k == doctest::Approx(std::round(k)).epsilon(1e-12).scale(1.0));
      }
  }
  CHECK(checked > 100);
}

TEST_CASE("Fabrication: rods that end at joints (valence 2 and 3) reach half an edge past them") {
  // grid(3, 4) without shear: straight rods whose ends are all joints
  // (valence 2 at the corners, 3 on the sides). docs/model.md section 3.2:
  // a segment of length L between two joints has edges h = L / (n - 1), and
  // a rod's terminal edge at a joint where it ends is its one segment's h,
  // centred on the joint.
  const int n = 4;
  const LineGraph graph = grid(3, 4, 0.0, 0.0);
  int checked = 0;
  for (RestShape rest : {RestShape::Straight, RestShape::Input}) {
    const RodLinkage linkage(graph, test_options(rest, n));
    const FabricationData data = fabrication_data(linkage);
    checked += check_invariants(linkage, data);
    REQUIRE(data.rods.size() == 7);  // 3 rows, 4 columns
    for (const FabricationRod& rod : data.rods) {
      CAPTURE(rod.rod);
      const std::vector<int> vertices = rod_vertices(linkage.topology(), rod.rod);
      REQUIRE(rod.stations.size() == vertices.size() + 2);
      const double edge = (graph.vertices[vertices[1]] - graph.vertices[vertices[0]]).norm();
      const double overhang = 0.5 * edge / (n - 1);
      CHECK(rod.stations.front().vertex == -1);
      CHECK(rod.stations.back().vertex == -1);
      double s = overhang;
      for (size_t k = 0; k < vertices.size(); ++k) {
        if (k > 0) s += (graph.vertices[vertices[k]] - graph.vertices[vertices[k - 1]]).norm();
        CHECK(rod.stations[k + 1].vertex == vertices[k]);
        CHECK(rod.stations[k + 1].s == doctest::Approx(s).epsilon(1e-13));
        ++checked;
      }
      CHECK(rod.length == doctest::Approx(s + overhang).epsilon(1e-13));
    }
    // Valences: a corner pins two rod ends, a side joint is inside one rod
    // and at an end of the other.
    int corners = 0, sides = 0;
    for (const FabricationJoint& joint : data.joints) {
      const auto is_end_joint = [&](int x) {
        const FabricationRod& rod = data.rods[joint.rod[x]];
        return rod.stations[1].joint == joint.joint ||
               rod.stations[rod.stations.size() - 2].joint == joint.joint;
      };
      const int ends = is_end_joint(0) + is_end_joint(1);
      if (joint.valence == 2) {
        CHECK(ends == 2);
        ++corners;
      } else if (joint.valence == 3) {
        CHECK(ends == 1);
        ++sides;
      } else {
        CHECK(ends == 0);
      }
    }
    CHECK(corners == 4);
    CHECK(sides == 6);
  }
  CHECK(checked > 50);
}

TEST_CASE(
    "Fabrication: invariants on crossings and tees and curved grids and closed rods and beams") {
  int checked = 0;
  for (const LineGraph& graph : {single_x(), tee(), grid(3, 4, 0.4), ring_with_spokes(), beam()})
    for (RestShape rest : {RestShape::Input, RestShape::Straight}) {
      const RodLinkage linkage(graph, test_options(rest, 5));
      checked += check_invariants(linkage, fabrication_data(linkage));
    }
  CHECK(checked > 150);
}

TEST_CASE("Fabrication: a closed rod is cut half an edge before its closing joint") {
  const LineGraph graph = ring_with_spokes();
  const RodLinkage linkage(graph, test_options(RestShape::Straight, 5));
  const FabricationData data = fabrication_data(linkage);
  REQUIRE(data.rods.size() == 9);
  int closed = 0;
  for (const FabricationRod& rod : data.rods) {
    if (!rod.closed) {
      // A spoke: its free end, then the ring joint it ends at, then the
      // overhang's tip.
      REQUIRE(rod.stations.size() == 3);
      CHECK(((rod.stations.front().vertex >= 8) != (rod.stations.back().vertex >= 8)));
      continue;
    }
    ++closed;
    REQUIRE(rod.stations.size() == 10);  // two ends, eight joints
    CHECK(rod.stations.front().vertex == -1);
    CHECK(rod.stations.back().vertex == -1);
    // The closing joint at half its terminal edge, h = L / (n - 1) for a
    // chord L of the octagon.
    const double edge = (graph.vertices[1] - graph.vertices[0]).norm();
    CHECK(rod.stations[1].s == doctest::Approx(0.5 * edge / 4.0).epsilon(1e-13));
    // Joints one (rest) chord apart, a little more than the drawn chord: the
    // terminal edges follow the octagon's tangent at the joints
    // (docs/model.md section 3.2); the same for every chord by symmetry.
    const double spacing = rod.stations[2].s - rod.stations[1].s;
    CHECK(spacing > edge);
    CHECK(spacing < 1.02 * edge);
    for (size_t k = 2; k < 9; ++k)
      CHECK(rod.stations[k].s - rod.stations[k - 1].s == doctest::Approx(spacing).epsilon(1e-12));
    CHECK(rod.length == doctest::Approx(8.0 * spacing).epsilon(1e-12));
  }
  CHECK(closed == 1);
}

TEST_CASE("Fabrication: families follow the joint labels and the two rods of a joint differ") {
  int checked = 0;
  for (const LineGraph& graph : {grid(3, 4, 0.4), grid(4, 5, 0.0, 0.3), ring_with_spokes()}) {
    const RodLinkage linkage(graph, test_options());
    const FabricationData data = fabrication_data(linkage);
    for (const FabricationRod& rod : data.rods) CHECK(rod.other_label_vertices.empty());
    for (const FabricationJoint& joint : data.joints) {
      CHECK(data.rods[joint.rod[0]].family == RodFamily::A);
      CHECK(data.rods[joint.rod[1]].family == RodFamily::B);
      ++checked;
    }
  }
  CHECK(checked > 20);
  CHECK(std::string(family_name(RodFamily::A)) == "A");
  CHECK(std::string(family_name(RodFamily::B)) == "B");
}

TEST_CASE(
    "Fabrication: the current opening angle moves with the state but the input one does not") {
  RodLinkage linkage(grid(3, 4, 0.2), test_options());
  const FabricationData before = fabrication_data(linkage);
  Eigen::VectorXd dofs = linkage.dofs();
  for (int j = 0; j < linkage.num_joints(); ++j) dofs[linkage.joint_dof_offset(j) + kAlpha] += 0.05;
  linkage.set_dofs(dofs);
  const FabricationData after = fabrication_data(linkage);
  int checked = 0;
  for (size_t j = 0; j < after.joints.size(); ++j) {
    CHECK(after.joints[j].angle_input == before.joints[j].angle_input);
    CHECK(after.joints[j].angle == doctest::Approx(before.joints[j].angle + 0.05).epsilon(1e-12));
    CHECK(before.joints[j].angle == doctest::Approx(before.joints[j].angle_input).epsilon(1e-12));
    ++checked;
  }
  // Rest lengths, so lengths and stations, do not move.
  for (size_t r = 0; r < after.rods.size(); ++r)
    CHECK(after.rods[r].length == before.rods[r].length);
  CHECK(checked == 12);
}

TEST_CASE("Fabrication: each rod's cross-section is its own material's") {
  const LineGraph graph = grid(3, 4);
  LinkageOptions options = test_options();
  const LinkageTopology topo = build_topology(graph);
  options.segment_materials.assign(graph.edges.size(), options.material);
  for (size_t r = 0; r < topo.rods.size(); ++r)
    for (int seg : topo.rods[r].segments) {
      options.segment_materials[seg].section.width = 0.01 * (r + 1);
      options.segment_materials[seg].section.shape =
          r % 2 ? SectionShape::Ellipse : SectionShape::Rectangle;
    }
  const RodLinkage linkage(graph, options);
  const FabricationData data = fabrication_data(linkage);
  for (size_t r = 0; r < data.rods.size(); ++r) {
    CHECK(data.rods[r].section.width == doctest::Approx(0.01 * (r + 1)));
    CHECK(data.rods[r].section.shape == (r % 2 ? SectionShape::Ellipse : SectionShape::Rectangle));
    CHECK(data.rods[r].section.height == options.material.section.height);
  }
  CHECK(data.rods.size() == 7);
}

// On the reference implementation's linkages: the invariants hold on real,
// curved designs with their valence 2 and 3 joints; reports how many rods
// carry both labels.
TEST_CASE("Fabrication: invariants on every real linkage" * doctest::test_suite("validation")) {
  const std::filesystem::path dir = XSHELL_SHARED_DATA_DIR;
  if (!std::filesystem::is_directory(dir)) XSHELL_SKIP(dir.string() + " is absent");
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  int built = 0;
  for (const auto& path : files) {
    CAPTURE(path.filename().string());
    const LineGraph graph = read_obj(path.string());
    LinkageOptions options;
    options.subdivisions = 4;
    options.material.section = {SectionShape::Rectangle, 10.0, 7.0};
    const RodLinkage linkage(graph, options);
    const FabricationData data = fabrication_data(linkage);
    check_invariants(linkage, data);
    int mixed = 0, closed = 0;
    for (const FabricationRod& rod : data.rods) {
      mixed += !rod.other_label_vertices.empty();
      closed += rod.closed;
    }
    MESSAGE(path.filename().string()
            << ": " << data.rods.size() << " rods, " << data.joints.size() << " joints, " << mixed
            << " rods with both labels, " << closed << " closed rods");
    ++built;
  }
  CHECK(built == static_cast<int>(files.size()));
}

}  // namespace xshell::test
