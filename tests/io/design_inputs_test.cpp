// The configuration's "transform", supports that "select" their vertices and
// "loads.line_loads": read and checked (config.hpp, config_parts.hpp),
// resolved against the linkage (support_selection.hpp) and handed to the
// model (problem_setup.hpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/problem_setup.hpp"
#include "io/support_selection.hpp"
#include "skip.hpp"

namespace xshell::test::design_inputs_test {
namespace {

using nlohmann::json;

json minimal() {
  return {
      {"linkage", "grid.obj"},
      {"material", {{"young_modulus", 2e4}, {"cross_section", {{"width", 10}, {"height", 7}}}}}};
}

Config parse(const json& document) { return parse_config(document.dump(), "c.json", ""); }

// The InputError message of parsing `document`, or of setting it up on
// `graph` when given; "" (and a failed check) when accepted.
std::string rejection(const json& document, const LineGraph* graph = nullptr) {
  try {
    const Config config = parse(document);
    if (graph) make_problem_setup(config, *graph);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL_CHECK("accepted: " << document.dump());
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  const bool found = text.find(part) != std::string::npos;
  if (!found) MESSAGE("\"" << part << "\" is not in: " << text);
  return found;
}

// 4 x 4 crossings 100 apart in z = 0 (vertex i * 4 + j at (100 j, 100 i)),
// with a free end sticking out of vertex 3 (vertex 16, at (400, 0)).
LineGraph grid_with_tail() {
  LineGraph g;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) g.vertices.emplace_back(100.0 * j, 100.0 * i, 0.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (j + 1 < 4) g.edges.push_back({i * 4 + j, i * 4 + j + 1});
      if (i + 1 < 4) g.edges.push_back({i * 4 + j, (i + 1) * 4 + j});
    }
  g.vertices.emplace_back(400.0, 0.0, 0.0);
  g.edges.push_back({3, 16});
  return g;
}

json support(const json& select, const json& fix = json::array({"position"})) {
  return {{"select", select}, {"fix", fix}};
}

}  // namespace

TEST_CASE("Design inputs: every form of \"select\" resolves to its vertices") {
  const LineGraph g = grid_with_tail();
  json document = minimal();
  document["supports"] = {support("boundary"),
                          support({{"valence", {2}}}),
                          support({{"region", {{"x_max", 50.0}, {"y_min", 100.0}}}}),
                          support(json::array({5, 1, 6})),
                          {{"vertex", 9}, {"fix", {"z"}}}};
  const Config config = parse(document);
  const std::vector<std::vector<int>> vertices = resolve_supports(config, g);
  REQUIRE(vertices.size() == 5);
  CHECK(vertices[0] == std::vector<int>{0, 1, 2, 3, 4, 7, 8, 11, 12, 13, 14, 15, 16});
  CHECK(vertices[1] == std::vector<int>{0, 12, 15});  // 3 has valence 3 with the tail
  CHECK(vertices[2] == std::vector<int>{4, 8, 12});   // x = 0, y >= 100: bounds included
  CHECK(vertices[3] == std::vector<int>{1, 5, 6});
  CHECK(vertices[4] == std::vector<int>{9});
  // The setup holds every resolved vertex and keeps the lists for the summary.
  const ProblemSetup setup = make_problem_setup(config, g);
  CHECK(setup.support_vertices == vertices);
  CHECK(setup.statics.supports.size() == 13 + 3 + 3 + 3 + 1);
  // Written back as given.
  const json resolved = to_json(config);
  CHECK(resolved["supports"][0]["select"] == "boundary");
  CHECK(resolved["supports"][2]["select"] ==
        json({{"region", {{"x_max", 50.0}, {"y_min", 100.0}}}}));
  CHECK(to_json(parse_config(resolved.dump(), "again.json", "")) == resolved);
}

TEST_CASE("Design inputs: selectors that are wrong or select nothing name their entry") {
  const LineGraph g = grid_with_tail();
  const auto with_supports = [](const std::vector<json>& supports) {
    json document = minimal();
    document["supports"] = supports;
    return document;
  };
  CHECK(
      contains(rejection(with_supports({{{"vertex", 1}, {"select", "boundary"}, {"fix", {"x"}}}})),
               "c.json: supports[0]: needs one of \"vertex\" and \"select\", not both"));
  CHECK(contains(rejection(with_supports({support("rim")})),
                 "c.json: supports[0].select: expected \"boundary\""));
  CHECK(contains(rejection(with_supports({support({{"valence", {5}}})})),
                 "supports[0].select.valence[0]: a valence must be in [1, 4], got 5"));
  CHECK(contains(rejection(with_supports({support({{"region", {{"z_min", 2}, {"z_max", 1}}}})})),
                 "supports[0].select.region: z_min is above z_max"));
  CHECK(contains(rejection(with_supports({support({{"region", {{"zmax", 2}}}})})),
                 "supports[0].select.region"));
  CHECK(contains(rejection(with_supports({support(json::array({1, 1}))})),
                 "supports[0].select[1]: vertex 1 is listed twice"));
  CHECK(contains(rejection(with_supports({support({{"x", 1}}), support("boundary")}), &g),
                 "supports[0].select"));
  CHECK(contains(
      rejection(with_supports({support(json::array({3})), support({{"region", {{"z_min", 5.0}}}})}),
                &g),
      "c.json: supports[1].select: selects no vertex of the linkage (17 vertices)"));
  CHECK(contains(rejection(with_supports({support(json::array({3, 40}))}), &g),
                 "c.json: supports[0].select[1]: vertex 40 is out of range"));
  // The free end is on the boundary, and has no opening angle.
  CHECK(
      contains(rejection(with_supports({support("boundary", json::array({"opening_angle"}))}), &g),
               "supports[0].fix[0]: \"opening_angle\": vertex 16 is a free rod end"));
  // Two entries displacing a common vertex differently, one a selector.
  CHECK(contains(rejection(with_supports({{{"vertex", 15}, {"fix", {"z"}}},
                                          {{"select", {{"valence", {2}}}},
                                           {"fix", {"position"}},
                                           {"displacement", {0, 0, 1}}}}),
                           &g),
                 "c.json: supports[1]: vertex 15 is also held by supports[0], and the two "
                 "displace its z component differently (0 and 1)"));
}

TEST_CASE("Design inputs: the transform comes first, regions see its coordinates") {
  const LineGraph g = grid_with_tail();
  json document = minimal();
  // Millimetres to metres, turned 90 degrees about z (x -> y), raised 1 m.
  document["transform"] = {{"scale", 1e-3}, {"rotate_deg", {0, 0, 90}}, {"translate", {0, 0, 1}}};
  document["supports"] = json::array({support({{"region", {{"y_min", 0.25}}}})});
  const Config config = parse(document);
  const ProblemSetup setup = make_problem_setup(config, g);
  // Vertices at input x >= 300 (3, 7, 11, 15 and the tail 16) are now at y >= 0.3.
  CHECK(setup.support_vertices[0] == std::vector<int>{3, 7, 11, 15, 16});
  const Eigen::Vector3d vertex_16 = setup.graph.vertices[16] + setup.origin;
  CHECK((vertex_16 - Eigen::Vector3d(0.0, 0.4, 1.0)).norm() < 1e-12);
  CHECK(to_json(config)["transform"] == json({{"mirror", nullptr},
                                              {"scale", 1e-3},
                                              {"rotate_deg", {0, 0, 90}},
                                              {"translate", {0, 0, 1}}}));
  CHECK_FALSE(to_json(parse(minimal())).contains("transform"));
  json bad = minimal();
  bad["transform"] = {{"scale", 0}};
  CHECK(contains(rejection(bad), "c.json: transform.scale: must be > 0, got 0"));
  bad["transform"] = {{"mirror", "w"}};
  CHECK(contains(rejection(bad), "transform.mirror: expected \"x\", \"y\" or \"z\""));
  bad["transform"] = {{"rotate", {0, 0, 1}}};
  CHECK(contains(rejection(bad), "unknown key \"rotate\" in transform"));
}

TEST_CASE("Design inputs: line loads are read, checked against the rods and handed on") {
  const LineGraph g = grid_with_tail();
  json document = minimal();
  document["loads"]["line_loads"] = {{{"rods", "all"}, {"force_per_length", {0, 0, -1}}},
                                     {{"rods", {0, 2}}, {"force_per_length", {1, 0, 0}}}};
  const Config config = parse(document);
  const ProblemSetup setup = make_problem_setup(config, g);
  REQUIRE(setup.statics.line_loads.size() == 2);
  CHECK(setup.statics.line_loads[0].rods.empty());
  CHECK(setup.statics.line_loads[1].rods == std::vector<int>{0, 2});
  CHECK(setup.statics.line_loads[0].force_per_length == Eigen::Vector3d(0, 0, -1));
  CHECK(to_json(config)["loads"]["line_loads"][0]["rods"] == "all");
  CHECK(to_json(parse_config(to_json(config).dump(), "again.json", "")) == to_json(config));
  json bad = minimal();
  bad["loads"]["line_loads"] = {{{"rods", {8}}, {"force_per_length", {0, 0, -1}}}};
  CHECK(contains(rejection(bad, &g),
                 "c.json: loads.line_loads[0].rods[0]: rod 8 is out of range; the linkage has 8 "
                 "rods"));
  bad["loads"]["line_loads"] = {{{"rods", json::array()}, {"force_per_length", {0, 0, -1}}}};
  CHECK(contains(rejection(bad), "loads.line_loads[0].rods: must list at least one rod"));
  bad["loads"]["line_loads"] = {{{"rods", "some"}, {"force_per_length", {0, 0, -1}}}};
  CHECK(contains(rejection(bad), "expected \"all\" or a list of rod indices"));
  bad["loads"]["line_loads"] = {{{"rods", "all"}}};
  CHECK(contains(rejection(bad), "missing required key \"loads.line_loads[0].force_per_length\""));
}

// The corners of the convex hull of the points (x, y) (Andrew's monotone
// chain): vertices that any walk around the outside must meet.
std::vector<int> hull_corners(const LineGraph& g) {
  std::vector<int> order(g.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  const auto at = [&g](int v) { return Eigen::Vector2d(g.vertices[v].x(), g.vertices[v].y()); };
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return at(a).x() < at(b).x() || (at(a).x() == at(b).x() && at(a).y() < at(b).y());
  });
  const auto turn = [&](int o, int a, int b) {
    const Eigen::Vector2d u = at(a) - at(o), w = at(b) - at(o);
    return u.x() * w.y() - u.y() * w.x();
  };
  std::vector<int> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (int v : order) {
      while (hull.size() >= base + 2 && turn(hull[hull.size() - 2], hull.back(), v) <= 0)
        hull.pop_back();
      hull.push_back(v);
    }
    hull.pop_back();
    std::reverse(order.begin(), order.end());
  }
  std::sort(hull.begin(), hull.end());
  return hull;
}

TEST_CASE("Design inputs: the boundary of the real designs") {
  namespace fs = std::filesystem;
  const fs::path folder = XSHELL_SHARED_DATA_DIR;
  if (!fs::is_directory(folder)) XSHELL_SKIP(folder.string() + " is absent");
  json document = minimal();
  document["supports"] = json::array({support("boundary")});
  const Config config = parse(document);
  const auto rim_and_low_valence = [&](const std::string& name) {
    const LineGraph g = read_obj((folder / name).string());
    std::vector<int> low;
    const std::vector<int> valence = valences(g);
    for (int v = 0; v < static_cast<int>(valence.size()); ++v)
      if (valence[v] < 4) low.push_back(v);
    const std::vector<int> rim = resolve_supports(config, g)[0];
    const std::vector<int> hull = hull_corners(g);  // the designs lie in planes z = const
    CHECK(std::includes(rim.begin(), rim.end(), hull.begin(), hull.end()));
    return std::make_pair(rim, low);
  };
  // The manta ray: exactly its 48 vertices of valence 2 and 3.
  const auto [manta_rim, manta_low] = rim_and_low_valence("manta_ray_5ca2f7ab.obj");
  CHECK(manta_rim == manta_low);
  CHECK(manta_rim.size() == 48);
  // darth_vader: its 42 vertices of valence 2 and 3, and 6 of valence 4 where
  // two rods cross on the rim itself.
  const auto [darth_rim, darth_low] = rim_and_low_valence("darth_vader_fig5_1693d9a2.obj");
  CHECK(std::includes(darth_rim.begin(), darth_rim.end(), darth_low.begin(), darth_low.end()));
  CHECK(darth_low.size() == 42);
  CHECK(darth_rim.size() == 48);
  // The largest design has two holes: their rims (of valence 2 and 3) are not
  // its boundary.
  const auto [large_rim, large_low] = rim_and_low_valence("large_6d35a972.obj");
  std::vector<int> holes;
  std::set_difference(large_low.begin(), large_low.end(), large_rim.begin(), large_rim.end(),
                      std::back_inserter(holes));
  CHECK(holes.size() == 18);
  CHECK(large_rim.size() == 128);
}

}  // namespace xshell::test::design_inputs_test
