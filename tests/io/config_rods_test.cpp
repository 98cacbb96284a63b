// The configuration's "rods": per-rod materials and their selectors.
#include <doctest/doctest.h>

#include "config_test_support.hpp"
#include "io/config.hpp"
#include "io/input_error.hpp"
#include "io/problem_setup.hpp"
#include "linkage/topology.hpp"

namespace xshell::test {

TEST_CASE("config: rods override the material of selected rods") {
  const json rods = json::parse(R"([
    {"rod": 1, "material": {"poisson_ratio": 0.2, "density": 3, "strength": 50,
                            "cross_section": {"shape": "ellipse", "height": 4}}},
    {"edges": [[0, 1], [3, 2]], "material": {"young_modulus": 1e5}},
    {"vertices": [4, 0], "material": {}}
  ])");
  const Config c = parse(with("/rods", rods));
  REQUIRE(c.rods.size() == 3);
  CHECK(c.rods[0].selector == RodSelector::Rod);
  CHECK(c.rods[0].rod == 1);
  const MaterialConfig& m = c.rods[0].material;
  CHECK(m.young_modulus == 2e4);  // inherited
  CHECK(m.poisson_ratio == 0.2);
  CHECK(m.density == 3);
  CHECK(m.strength == 50.0);
  CHECK(m.cross_section.shape == SectionShape::Ellipse);
  CHECK(m.cross_section.width == 10);  // inherited
  CHECK(m.cross_section.height == 4);
  CHECK(c.rods[1].selector == RodSelector::Edges);
  CHECK(c.rods[1].edges == std::vector<std::array<int, 2>>{{0, 1}, {3, 2}});
  CHECK(c.rods[1].material.young_modulus == 1e5);
  CHECK(c.rods[1].material.cross_section.height == 7);
  CHECK_FALSE(c.rods[1].material.strength.has_value());
  CHECK(c.rods[2].selector == RodSelector::Vertices);
  CHECK(c.rods[2].vertices == std::vector<int>{4, 0});
  CHECK(c.rods[2].material.cross_section.width == 10);
  // Resolved (every key filled in), and read back the same.
  const json resolved = to_json(c);
  CHECK(resolved["rods"][1]["material"]["cross_section"]["height"] == 7.0);
  CHECK(resolved["rods"][0]["rod"] == 1);
  CHECK(to_json(parse_config(resolved.dump(), "again.json", "/elsewhere")) == resolved);
}

TEST_CASE("config: bad rods entries are rejected") {
  const json material = {{"young_modulus", 1}};
  const std::vector<std::pair<json, std::vector<std::string>>> cases = {
      {{{{"material", material}}}, {"rods[0]: needs exactly one selector"}},
      {{{{"rod", 0}, {"vertices", {1}}, {"material", material}}},
       {"rods[0]: needs exactly one selector"}},
      {{{{"rod", 0}}}, {"missing required key \"rods[0].material\""}},
      {{{{"rod", -1}, {"material", material}}}, {"rods[0].rod: a rod index is 0-based"}},
      {{{{"rod", 0.5}, {"material", material}}}, {"rods[0].rod", "expected an integer"}},
      {{{{"rods", 0}, {"material", material}}},
       {"unknown key \"rods\" in rods[0]", "did you mean \"rod\"?"}},
      {{{{"rod", 0}, {"material", {{"young_modulos", 1}}}}},
       {"in rods[0].material", "did you mean \"young_modulus\"?"}},
      {{{{"rod", 0}, {"material", {{"cross_section", {{"widht", 1}}}}}}},
       {"in rods[0].material.cross_section", "did you mean \"width\"?"}},
      {{{{"rod", 0}, {"material", {{"young_modulus", -3}}}}},
       {"rods[0].material.young_modulus: must be > 0"}},
      {{{{"rod", 0}, {"material", {{"cross_section", {{"height", 0}}}}}}},
       {"rods[0].material.cross_section.height: must be > 0"}},
      {{{{"edges", json::array()}, {"material", material}}},
       {"rods[0].edges: must list at least one edge"}},
      {{{{"edges", {{1, 2, 3}}}, {"material", material}}},
       {"rods[0].edges[0]: expected an edge [i, j]"}},
      {{{{"edges", {{1, 2}, {2, 1}}}, {"material", material}}},
       {"rods[0].edges[1]: edge [2, 1] is listed twice"}},
      {{{{"edges", {{1, -2}}}, {"material", material}}}, {"rods[0].edges[0][1]: a vertex index"}},
      {{{{"vertices", json::array()}, {"material", material}}},
       {"rods[0].vertices: must list at least one"}},
      {{{{"vertices", {3, 3}}, {"material", material}}},
       {"rods[0].vertices[1]: vertex 3 is listed twice"}},
      {{{{"vertices", {"a"}}, {"material", material}}}, {"rods[0].vertices[0]", "expected"}},
      {json::object(), {"rods", "expected an array"}},
  };
  for (const auto& [rods, words] : cases) {
    INFO(rods.dump());
    check_message(rejection(with("/rods", rods)), words);
  }
  CHECK(cases.size() == 18);
  // Non-finite numbers: as everywhere.
  const std::string text = R"({"linkage": "a.obj", "material": {"young_modulus": 1,
    "cross_section": {"width": 1, "height": 1}}, "rods": [{"rod": 0, "material": {"density": -1e999}}]})";
  check_message(rejection(text), {"rods[0].material.density", "overflows to infinity"});
}

TEST_CASE("config: support displacements move only held components") {
  const json pushed = {{{"vertex", 1}, {"fix", {"x", "z"}}, {"displacement", {0.5, 0, -2}}}};
  const Config c = parse(with("/supports", pushed));
  CHECK(c.supports[0].displacement == Eigen::Vector3d(0.5, 0, -2));
  CHECK(to_json(c)["supports"][0]["displacement"] == json({0.5, 0.0, -2.0}));
  CHECK(parse(with("/supports",
                   {{{"vertex", 1}, {"fix", {"position"}}, {"displacement", {1, 2, 3}}}}))
            .supports[0]
            .displacement == Eigen::Vector3d(1, 2, 3));
  check_message(
      rejection(
          with("/supports", {{{"vertex", 1}, {"fix", {"x", "z"}}, {"displacement", {0, 1, 0}}}})),
      {"supports[0].displacement[1]: moves the y component", "leaves free",
       "\"position\" or \"y\""});
  check_message(
      rejection(with("/supports",
                     {{{"vertex", 1}, {"fix", {"orientation"}}, {"displacement", {1, 0, 0}}}})),
      {"supports[0].displacement[0]: moves the x component"});
  check_message(
      rejection(with("/supports", {{{"vertex", 1}, {"fix", {"z"}}, {"displacement", {0, 1}}}})),
      {"supports[0].displacement", "three numbers"});
  check_message(
      rejection(with("/supports", {{{"vertex", 1}, {"fix", {"z"}}, {"displacment", {0, 0, 1}}}})),
      {"in supports[0]", "did you mean \"displacement\"?"});
  const std::string infinite =
      R"({"supports": [{"vertex": 1, "fix": ["z"], "displacement": [0, 0, 1e999]}]})";
  check_message(rejection(infinite), {"supports[0].displacement[2]", "overflows to infinity"});
}

TEST_CASE("config: rods selectors resolve to segments, bad rods and edges are named") {
  // Two rods crossing at vertex 0: rod of edges 0-1 (1-0-2) and of 2-3 (3-0-4).
  LineGraph graph;
  graph.vertices = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
  graph.edges = {{1, 0}, {0, 2}, {3, 0}, {0, 4}};
  const LinkageTopology topology = build_topology(graph);
  REQUIRE(topology.rods.size() == 2);
  const int rod_x = topology.segments[0].rod, rod_y = topology.segments[2].rod;
  REQUIRE(rod_x != rod_y);
  auto widths = [&](const json& rods) {
    const Config c = parse(with("/rods", rods));
    check_vertices(c, graph);
    std::vector<double> w;
    for (const Material& m : segment_materials(c, graph, topology)) w.push_back(m.section.width);
    return w;
  };
  const json narrow = {{"cross_section", {{"width", 3}}}};
  const json wide = {{"cross_section", {{"width", 30}}}};
  CHECK(widths(json::array()) == std::vector<double>{10, 10, 10, 10});
  CHECK(widths({{{"rod", rod_y}, {"material", narrow}}}) == std::vector<double>{10, 10, 3, 3});
  // An edge selects the whole rod that contains it.
  CHECK(widths({{{"edges", {{2, 0}}}, {"material", narrow}}}) == std::vector<double>{3, 3, 10, 10});
  // A vertex selects every rod through it (a free end: its own rod).
  CHECK(widths({{{"vertices", {4}}, {"material", narrow}}}) == std::vector<double>{10, 10, 3, 3});
  CHECK(widths({{{"vertices", {0}}, {"material", narrow}}}) == std::vector<double>{3, 3, 3, 3});
  // Later entries win.
  CHECK(widths({{{"vertices", {0}}, {"material", narrow}}, {{"rod", rod_x}, {"material", wide}}}) ==
        std::vector<double>{30, 30, 3, 3});
  CHECK(widths({{{"rod", rod_x}, {"material", wide}}, {{"vertices", {0}}, {"material", narrow}}}) ==
        std::vector<double>{3, 3, 3, 3});

  const Config out_of_range = parse(with("/rods", {{{"rod", 2}, {"material", narrow}}}));
  CHECK_THROWS_WITH_AS(
      segment_materials(out_of_range, graph, topology),
      doctest::Contains("c.json: rods[0].rod: rod 2 is out of range; the linkage has 2 rods"),
      InputError);
  const Config no_edge =
      parse(with("/rods", {{{"edges", {{0, 1}, {1, 2}}}, {"material", narrow}}}));
  CHECK_THROWS_WITH_AS(
      segment_materials(no_edge, graph, topology),
      "c.json: rods[0].edges[1]: vertices 1 and 2 are not joined by an edge of the linkage",
      InputError);
  const Config bad_vertex = parse(with("/rods", {{{"vertices", {0, 5}}, {"material", narrow}}}));
  CHECK_THROWS_WITH_AS(check_vertices(bad_vertex, graph),
                       doctest::Contains("c.json: rods[0].vertices[1]: vertex 5 is out of range"),
                       InputError);
  const Config bad_edge = parse(with("/rods", {{{"edges", {{0, 9}}}, {"material", narrow}}}));
  CHECK_THROWS_WITH_AS(check_vertices(bad_edge, graph),
                       doctest::Contains("c.json: rods[0].edges[0][1]: vertex 9 is out of range"),
                       InputError);
}

}  // namespace xshell::test
