#include "io/config.hpp"

#include <doctest/doctest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>

#include "config_test_support.hpp"
#include "io/input_error.hpp"
#include "io/problem_setup.hpp"
#include "linkage/topology.hpp"
#include "scratch_directory.hpp"

namespace xshell::test {
namespace {

const json kFull = json::parse(R"({
  "linkage": "../meshes/grid.obj",
  "subdivisions": 12,
  "rest_shape": "straight",
  "joints": "edge_vectors",
  "material": {"young_modulus": 25000, "poisson_ratio": 0.25, "density": 7.85e-9,
               "strength": 300,
               "cross_section": {"shape": "ellipse", "width": 12, "height": 8}},
  "rods": [{"vertices": [2], "material": {"young_modulus": 30000, "cross_section": {"width": 20}}}],
  "supports": [{"vertex": 0, "fix": ["position", "orientation"]},
               {"vertex": 4, "fix": ["z"], "displacement": [0, 0, -1.5]}],
  "loads": {"gravity": [0, 0, -9810], "forces": [{"vertex": 3, "force": [1, 2, 3]}]},
  "solver": {"method": "kinetic-damping", "gradient_tolerance": 1e-8, "max_iterations": 50,
             "mass": "fictitious", "damping": 0.5, "first_order": true, "start": "rest", "max_steps": 700,
             "line_search": "kinsol", "escape_saddles": false, "buckling_direction": [0, 0, -2]},
  "output": {"directory": "/tmp/results", "every": 5, "format": "ascii", "compression": "zlib",
             "solids": true,
             "progress": false},
  "deployment": {"joint_angles": [{"vertex": 2, "angle": 1.5}, {"vertex": 3, "angle": 2}],
                 "steps": 7, "largest_step": 0.3}
})");

}  // namespace

// ---------------------------------------------------------------------------
// Accepted configurations

TEST_CASE("config: defaults are filled in") {
  const Config c = parse(kMinimal);
  CHECK(c.source == "c.json");
  CHECK(c.linkage == "/runs/a/grid.obj");
  CHECK(c.subdivisions == 8);
  CHECK(c.rest_shape == RestShape::Input);
  CHECK(c.joints == JointModel::Rotation);
  CHECK(c.material.young_modulus == 2e4);
  CHECK(c.material.poisson_ratio == 0.3);
  CHECK(c.material.density == 0);
  CHECK_FALSE(c.material.strength.has_value());
  CHECK(c.material.cross_section.shape == SectionShape::Rectangle);
  CHECK(c.material.cross_section.width == 10);
  CHECK(c.material.cross_section.height == 7);
  CHECK(c.supports.empty());
  CHECK(c.rods.empty());
  CHECK(c.loads.gravity == Eigen::Vector3d::Zero());
  CHECK(c.loads.forces.empty());
  CHECK(c.solver.method == SolverMethod::Newton);
  CHECK(c.solver.gradient_tolerance == 1e-6);
  CHECK(c.solver.max_iterations == 300);
  CHECK(c.solver.mass == MassSetting::Physical);
  CHECK_FALSE(c.solver.damping.has_value());
  CHECK_FALSE(c.solver.first_order);
  CHECK(c.solver.start == StartSetting::SlowManifold);
  CHECK(!c.solver.max_steps);
  CHECK(c.solver.step_limit() == 5000);
  CHECK(c.solver.line_search == LineSearchSetting::Energy);
  CHECK(c.solver.escape_saddles);
  CHECK(c.solver.buckling_direction == Eigen::Vector3d(0, 0, 1));
  CHECK(c.output.directory == "/runs/a/out");
  CHECK(c.output.every == 1);
  CHECK(c.output.format == OutputFormat::Binary);
  CHECK(c.output.compression == OutputCompression::Lz4);
  CHECK(c.output.solids == Toggle::Auto);
  CHECK(c.output.progress == Toggle::Auto);
  CHECK_FALSE(c.deployment.has_value());
}

TEST_CASE("config: every key is read") {
  const Config c = parse(kFull);
  CHECK(c.subdivisions == 12);
  CHECK(c.rest_shape == RestShape::Straight);
  CHECK(c.joints == JointModel::EdgeVectors);
  CHECK(c.material.poisson_ratio == 0.25);
  CHECK(c.material.density == 7.85e-9);
  CHECK(c.material.strength == 300.0);
  CHECK(c.material.cross_section.shape == SectionShape::Ellipse);
  REQUIRE(c.supports.size() == 2);
  CHECK(c.supports[0].vertex == 0);
  CHECK(c.supports[0].fix == std::vector<Fixed>{Fixed::Position, Fixed::Orientation});
  CHECK(c.supports[1].fix == std::vector<Fixed>{Fixed::Z});
  CHECK(c.supports[0].displacement == Eigen::Vector3d::Zero());
  CHECK(c.supports[1].displacement == Eigen::Vector3d(0, 0, -1.5));
  REQUIRE(c.rods.size() == 1);
  CHECK(c.rods[0].selector == RodSelector::Vertices);
  CHECK(c.rods[0].vertices == std::vector<int>{2});
  CHECK(c.rods[0].material.young_modulus == 30000);
  CHECK(c.rods[0].material.cross_section.width == 20);
  CHECK(c.rods[0].material.cross_section.height == 8);  // inherited, key by key
  CHECK(c.rods[0].material.cross_section.shape == SectionShape::Ellipse);
  CHECK(c.rods[0].material.density == 7.85e-9);
  CHECK(c.rods[0].material.strength == 300.0);
  CHECK(c.loads.gravity == Eigen::Vector3d(0, 0, -9810));
  REQUIRE(c.loads.forces.size() == 1);
  CHECK(c.loads.forces[0].vertex == 3);
  CHECK(c.loads.forces[0].force == Eigen::Vector3d(1, 2, 3));
  CHECK(c.solver.method == SolverMethod::KineticDamping);
  CHECK(c.solver.gradient_tolerance == 1e-8);
  CHECK(c.solver.max_iterations == 50);
  CHECK(c.solver.mass == MassSetting::Fictitious);
  CHECK(c.solver.damping == 0.5);
  CHECK(c.solver.first_order);
  CHECK(c.solver.start == StartSetting::Rest);
  CHECK(c.solver.line_search == LineSearchSetting::Kinsol);
  CHECK(c.solver.step_limit() == 700);
  CHECK_FALSE(c.solver.escape_saddles);
  CHECK(c.solver.buckling_direction == Eigen::Vector3d(0, 0, -2));
  CHECK(c.output.directory == "/tmp/results");
  CHECK(c.output.every == 5);
  CHECK(c.output.format == OutputFormat::Ascii);
  CHECK(c.output.compression == OutputCompression::Zlib);
  CHECK(c.output.solids == Toggle::On);
  CHECK(c.output.progress == Toggle::Off);
  REQUIRE(c.deployment.has_value());
  CHECK(c.deployment->target == DeploymentTarget::JointAngles);
  REQUIRE(c.deployment->joint_angles.size() == 2);
  CHECK(c.deployment->joint_angles[1].vertex == 3);
  CHECK(c.deployment->joint_angles[1].angle == 2);
  CHECK(c.deployment->steps == 7);
  CHECK(c.deployment->largest_step == 0.3);

  const Config average = parse(with("/deployment", {{"average_opening_angle", 1.2}}));
  REQUIRE(average.deployment.has_value());
  CHECK(average.deployment->target == DeploymentTarget::AverageOpeningAngle);
  CHECK(average.deployment->average_opening_angle == 1.2);
  CHECK(average.deployment->steps == 20);
  CHECK(average.deployment->largest_step == 0);  // equal increments
  CHECK(parse(with("/solver/damping", "auto")).solver.damping == std::nullopt);
  CHECK(parse(with("/subdivisions", 3.0)).subdivisions == 3);  // an integral number
}

TEST_CASE("config: paths are resolved against the configuration's folder") {
  CHECK(parse(kFull).linkage == "/runs/meshes/grid.obj");
  CHECK(parse(with("/linkage", "/abs/x.obj")).linkage == "/abs/x.obj");
  CHECK(parse(with("/output", {{"directory", "res/1"}})).output.directory == "/runs/a/res/1");
  const Config here = parse_config(kMinimal.dump(), "c.json", "");
  CHECK(here.linkage == "grid.obj");
  CHECK(here.output.directory == "out");

  namespace fs = std::filesystem;
  const ScratchDirectory scratch("config");
  const fs::path& dir = scratch.path();
  const fs::path file = dir / "run.json";
  std::ofstream(file) << kMinimal.dump(2);
  const Config c = read_config(file.string());
  CHECK(c.source == file.string());
  CHECK(c.linkage == (dir / "grid.obj").string());
  CHECK(c.output.directory == (dir / "out").string());
  fs::remove(file);
  const std::string expected = "cannot open configuration file '" + file.string() + "'";
  CHECK_THROWS_WITH_AS(read_config(file.string()), doctest::Contains(expected.c_str()), InputError);
}

TEST_CASE("config: to_json gives the resolved configuration back") {
  const json minimal = to_json(parse(kMinimal));
  CHECK(minimal["linkage"] == "/runs/a/grid.obj");
  CHECK(minimal["solver"]["damping"] == "auto");
  CHECK(minimal["solver"]["start"] == "slow_manifold");
  CHECK(minimal["solver"]["escape_saddles"] == true);
  CHECK(minimal["solver"]["buckling_direction"] == json({0.0, 0.0, 1.0}));
  CHECK(minimal["output"]["solids"] == "auto");
  CHECK(minimal["supports"] == json::array());
  CHECK(minimal["loads"]["gravity"] == json({0.0, 0.0, 0.0}));
  CHECK_FALSE(minimal["material"].contains("strength"));
  CHECK_FALSE(minimal.contains("deployment"));

  int round_trips = 0;
  for (const json& document :
       {kMinimal, kFull, with("/deployment", {{"average_opening_angle", 1}})}) {
    const json resolved = to_json(parse(document));
    // Parsed again from another folder: the stored paths are already resolved.
    CHECK(to_json(parse_config(resolved.dump(), "again.json", "/elsewhere")) == resolved);
    ++round_trips;
  }
  CHECK(round_trips == 3);
  CHECK(to_json(parse(kFull))["output"]["progress"] == false);
  CHECK(to_json(parse(kFull))["solver"]["damping"] == 0.5);
}

// ---------------------------------------------------------------------------
// Rejected configurations

TEST_CASE("config: JSON syntax errors give line and column") {
  const std::string text = "{\n  \"linkage\": \"a.obj\",\n  \"subdivisions\": 8,,\n}";
  check_message(rejection(text), {"c.json:3:21:", "invalid JSON"});
  check_message(rejection(std::string("{\"linkage\": \"a.obj\"")), {"c.json:1:20:"});
  check_message(rejection(std::string("")), {"c.json:1:1:"});
}

TEST_CASE("config: the document must be an object") {
  check_message(rejection(std::string("[1, 2]")), {"must be a JSON object", "array"});
}

TEST_CASE("config: unknown keys are rejected with the closest valid key") {
  check_message(rejection(with("/linkge", "x.obj")),
                {"unknown key \"linkge\" at the top level", "did you mean \"linkage\"?"});
  check_message(rejection(with("/material/young_modulous", 1)),
                {"unknown key \"young_modulous\" in material", "did you mean \"young_modulus\"?"});
  check_message(rejection(with("/material/cross_section/hieght", 1)),
                {"in material.cross_section", "did you mean \"height\"?"});
  check_message(rejection(with("/supports", {{{"vertex", 0}, {"fixed", {"x"}}}})),
                {"in supports[0]", "did you mean \"fix\"?"});
  check_message(rejection(with("/colour", "red")),
                {"unknown key \"colour\"", "valid keys are \"linkage\", \"subdivisions\""});
}

TEST_CASE("config: a key given twice is rejected") {
  const std::string text = R"({"linkage": "a.obj", "material": {"density": 1, "density": 2}})";
  check_message(rejection(text), {"material.density", "given twice"});
}

TEST_CASE("config: wrong types are rejected") {
  check_message(rejection(with("/material/young_modulus", "2e4")),
                {"material.young_modulus", "expected a number", "a string (\"2e4\")"});
  check_message(rejection(with("/subdivisions", 8.5)), {"subdivisions", "expected an integer"});
  check_message(rejection(with("/linkage", 3)), {"linkage", "expected a string"});
  check_message(rejection(with("/solver", {{"first_order", "yes"}})),
                {"solver.first_order", "expected true or false"});
  check_message(rejection(with("/material", json::array())), {"material", "expected an object"});
  check_message(rejection(with("/supports", json::object())), {"supports", "expected an array"});
  check_message(rejection(with("/loads", {{"gravity", {0, -9.8}}})),
                {"loads.gravity", "three numbers", "array of 2"});
  check_message(rejection(with("/loads", {{"gravity", {0, "down", 0}}})),
                {"loads.gravity[1]", "expected a number"});
  check_message(rejection(with("/output", {{"solids", "maybe"}})),
                {"output.solids", "expected true, false or \"auto\""});
  check_message(rejection(with("/solver", {{"damping", "fast"}})),
                {"solver.damping", "expected a number >= 0 or \"auto\""});
  check_message(rejection(with("/material/strength", nullptr)),
                {"material.strength", "expected a number, got null"});
  check_message(rejection(with("/solver", {{"escape_saddles", "yes"}})),
                {"solver.escape_saddles", "expected true or false"});
  check_message(rejection(with("/solver", {{"buckling_direction", {0, 1}}})),
                {"solver.buckling_direction", "three numbers", "array of 2"});
  check_message(rejection(with("/solver", {{"buckling_direction", {0, "up", 0}}})),
                {"solver.buckling_direction[1]", "expected a number"});
  check_message(rejection(with("/solver", {{"buckling_direction", "up"}})),
                {"solver.buckling_direction", "three numbers"});
}

TEST_CASE("config: a buckling direction must not be zero") {
  for (const json& zero : {json({0, 0, 0}), json({0.0, -0.0, 1e-320})}) {
    CAPTURE(zero.dump());
    check_message(rejection(with("/solver", {{"buckling_direction", zero}})),
                  {"solver.buckling_direction", "expected a non-zero direction"});
  }
}

TEST_CASE("config: missing required keys are rejected") {
  const std::vector<std::pair<json, std::string>> cases = {
      {without("/linkage"), "\"linkage\""},
      {without("/material"), "\"material\""},
      {without("/material/young_modulus"), "\"material.young_modulus\""},
      {without("/material/cross_section"), "\"material.cross_section\""},
      {without("/material/cross_section/width"), "\"material.cross_section.width\""},
      {without("/material/cross_section/height"), "\"material.cross_section.height\""},
      {with("/supports", {{{"fix", {"x"}}}}), "\"supports[0].vertex\""},
      {with("/supports", {{{"vertex", 1}}}), "\"supports[0].fix\""},
      {with("/loads", {{"forces", {{{"vertex", 1}}}}}), "\"loads.forces[0].force\""},
      {with("/deployment", {{"joint_angles", {{{"vertex", 1}}}}}),
       "\"deployment.joint_angles[0].angle\""},
  };
  for (const auto& [document, key] : cases)
    check_message(rejection(document), {"missing required key " + key});
  CHECK(cases.size() == 10);
}

TEST_CASE("config: out-of-range values are rejected") {
  struct Case {
    std::string pointer;
    json value;
    std::string expected;  // the key's path and the rule
  };
  const std::vector<Case> cases = {
      {"/material/young_modulus", -2e4, "material.young_modulus: must be > 0, got -20000"},
      {"/material/young_modulus", 0, "material.young_modulus: must be > 0"},
      {"/material/poisson_ratio", 0.5, "material.poisson_ratio: must be in (-1, 0.5), got 0.5"},
      {"/material/poisson_ratio", -1, "material.poisson_ratio: must be in (-1, 0.5)"},
      {"/material/density", -1, "material.density: must be >= 0"},
      {"/material/strength", 0, "material.strength: must be > 0"},
      {"/material/cross_section/width", -10, "material.cross_section.width: must be > 0"},
      {"/material/cross_section/height", 0, "material.cross_section.height: must be > 0"},
      {"/subdivisions", 2, "subdivisions: must be >= 3, got 2"},
      {"/subdivisions", 1e10, "subdivisions: integer 10000000000.0 is out of range"},
      {"/solver/gradient_tolerance", 0, "solver.gradient_tolerance: must be > 0"},
      {"/solver/max_iterations", 0, "solver.max_iterations: must be >= 1"},
      {"/solver/max_steps", -5, "solver.max_steps: must be >= 1"},
      {"/solver/damping", -0.1, "solver.damping: must be >= 0"},
      {"/output/every", 0, "output.every: must be >= 1"},
      {"/supports", {{{"vertex", -1}, {"fix", {"x"}}}}, "supports[0].vertex: a vertex index"},
      {"/loads/forces", {{{"vertex", -2}, {"force", {0, 0, 1}}}}, "loads.forces[0].vertex"},
      {"/deployment",
       {{"average_opening_angle", 0}},
       "deployment.average_opening_angle: must be in (0, pi) radians, got 0"},
      {"/deployment", {{"average_opening_angle", 3.15}}, "deployment.average_opening_angle"},
      {"/deployment",
       {{"joint_angles", {{{"vertex", 1}, {"angle", -1}}}}},
       "deployment.joint_angles[0].angle: must be in (0, pi)"},
      {"/deployment",
       {{"average_opening_angle", 1}, {"steps", 0}},
       "deployment.steps: must be >= 1"},
      {"/deployment",
       {{"average_opening_angle", 1}, {"largest_step", 0}},
       "deployment.largest_step: must be > 0, got 0"},
  };
  for (const Case& c : cases) {
    INFO(c.pointer << " = " << c.value.dump());
    check_message(rejection(with(c.pointer, c.value)), {"c.json: " + c.expected});
  }
  CHECK(cases.size() == 22);
}

TEST_CASE("config: infinite numbers are rejected") {
  const std::string text = R"({"linkage": "a.obj", "material": {"young_modulus": 1e999}})";
  check_message(rejection(text),
                {"material.young_modulus: number 1e999 out of range", "overflows to infinity"});
  const std::string in_array = R"({"loads": {"gravity": [0, -1e999, 0]}})";
  check_message(rejection(in_array), {"loads.gravity[1]", "overflows to infinity"});
}

TEST_CASE("config: bad enum strings list the valid choices") {
  check_message(rejection(with("/solver", {{"method", "newtn"}})),
                {"solver.method: \"newtn\" is not a valid choice",
                 "\"newton\", \"dynamics\", \"kinetic-damping\""});
  check_message(rejection(with("/rest_shape", "flat")), {"rest_shape", "\"input\", \"straight\""});
  check_message(rejection(with("/joints", "pins")), {"joints", "\"rotation\", \"edge_vectors\""});
  check_message(rejection(with("/material/cross_section/shape", "circle")),
                {"material.cross_section.shape", "\"rectangle\", \"ellipse\""});
  check_message(rejection(with("/output", {{"format", "xml"}})), {"output.format", "\"binary\""});
  check_message(rejection(with("/output", {{"compression", "gzip"}})),
                {"output.compression", "\"lz4\", \"zlib\", \"none\""});
  check_message(rejection(with("/solver", {{"mass", "real"}})), {"solver.mass", "\"fictitious\""});
  check_message(rejection(with("/solver", {{"start", "still"}})),
                {"solver.start", "\"slow_manifold\", \"rest\""});
  check_message(rejection(with("/supports", {{{"vertex", 1}, {"fix", {"x", "rotation"}}}})),
                {"supports[0].fix[1]: \"rotation\"", "\"opening_angle\""});
}

TEST_CASE("config: supports need distinct, non-empty fix lists") {
  check_message(rejection(with("/supports", {{{"vertex", 1}, {"fix", json::array()}}})),
                {"supports[0].fix: must list at least one"});
  check_message(rejection(with("/supports", {{{"vertex", 1}, {"fix", {"x", "y", "x"}}}})),
                {"supports[0].fix[2]: \"x\" is listed twice"});
}

TEST_CASE("config: deployment takes exactly one target") {
  check_message(rejection(with("/deployment", {{"steps", 3}})),
                {"deployment: needs \"average_opening_angle\" or \"joint_angles\""});
  check_message(rejection(with("/deployment", {{"average_opening_angle", 1},
                                               {"joint_angles", {{{"vertex", 1}, {"angle", 1}}}}})),
                {"deployment: gives both"});
  check_message(rejection(with("/deployment", {{"joint_angles", json::array()}})),
                {"deployment.joint_angles: must list at least one joint"});
  check_message(rejection(with("/deployment",
                               {{"joint_angles",
                                 {{{"vertex", 1}, {"angle", 1}}, {{"vertex", 1}, {"angle", 2}}}}})),
                {"deployment.joint_angles[1].vertex: vertex 1 is listed twice"});
}

TEST_CASE("config: check_vertices names the key of an index out of range") {
  LineGraph graph;
  graph.vertices.assign(5, Eigen::Vector3d::Zero());
  const Config full = parse(kFull);  // vertices 0, 4, 3, 2, 3: all in range
  CHECK_NOTHROW(check_vertices(full, graph));

  Config c = full;
  c.supports[1].vertex = 5;
  CHECK_THROWS_WITH_AS(check_vertices(c, graph),
                       "c.json: supports[1].vertex: vertex 5 is out of range; the linkage has 5 "
                       "vertices (0-based indices 0 to 4)",
                       InputError);
  c = full;
  c.loads.forces[0].vertex = 9;
  CHECK_THROWS_WITH_AS(check_vertices(c, graph), doctest::Contains("loads.forces[0].vertex"),
                       InputError);
  c = full;
  c.deployment->joint_angles[1].vertex = 100;
  CHECK_THROWS_WITH_AS(check_vertices(c, graph),
                       doctest::Contains("deployment.joint_angles[1].vertex: vertex 100"),
                       InputError);
}

TEST_CASE("config: one vertex in two supports displaced differently names both entries") {
  // Different components, or equal displacements: both entries apply.
  CHECK(parse(with("/supports", {{{"vertex", 1}, {"fix", {"x"}}, {"displacement", {1, 0, 0}}},
                                 {{"vertex", 1}, {"fix", {"z"}}, {"displacement", {0, 0, 2}}}}))
            .supports.size() == 2);
  CHECK(parse(with("/supports", {{{"vertex", 1}, {"fix", {"position"}}},
                                 {{"vertex", 1}, {"fix", {"orientation"}}}}))
            .supports.size() == 2);
  // The same component held at two displacements: which wins would be an
  // accident of order.
  check_message(
      rejection(
          with("/supports", {{{"vertex", 3}, {"fix", {"position"}}, {"displacement", {0, 0, -0.5}}},
                             {{"vertex", 1}, {"fix", {"x"}}},
                             {{"vertex", 3}, {"fix", {"z"}}, {"displacement", {0, 0, 0.25}}}})),
      {"c.json: supports[2]: vertex 3 is also held by supports[0]", "z component",
       "-0.5 and 0.25"});
  check_message(
      rejection(with("/supports",
                     {{{"vertex", 3}, {"fix", {"position"}}},
                      {{"vertex", 3}, {"fix", {"position"}}, {"displacement", {0.1, 0, 0}}}})),
      {"supports[1]: vertex 3 is also held by supports[0]", "x component"});
}

TEST_CASE("config: a file name with a NUL byte is refused and not cut short") {
  const std::string message = rejection(with("/linkage", std::string("grid\0.obj", 9)));
  check_message(message, {"c.json: linkage: a file name cannot contain a NUL byte", "grid\\0.obj"});
  CHECK(message.find('\0') == std::string::npos);
}

TEST_CASE("config: supports that cannot apply are named by their key and not blamed on the OBJ") {
  LineGraph graph;  // one X joint (vertex 2) and four free ends
  graph.vertices = {{-1, -1, 0}, {1, 1, 0}, {0, 0, 0}, {1, -1, 0}, {-1, 1, 0}};
  graph.edges = {{0, 2}, {2, 1}, {3, 2}, {2, 4}};
  auto setup_error = [&](const json& document) -> std::string {
    const Config c = parse(document);
    try {
      make_problem_setup(c, graph);
    } catch (const InputError& e) {
      return e.what();
    }
    FAIL_CHECK("accepted: " << document.dump());
    return "";
  };
  // Everything fixed at a free end: it has no opening angle.
  check_message(
      setup_error(with("/supports",
                       {{{"vertex", 2}, {"fix", {"position"}}},
                        {{"vertex", 0}, {"fix", {"position", "orientation", "opening_angle"}}}})),
      {"c.json: supports[1].fix[2]: \"opening_angle\": vertex 0 is a free rod end"});
  // An opening angle at an edge-vector joint.
  json edge_vectors = with("/supports", {{{"vertex", 2}, {"fix", {"opening_angle"}}}});
  edge_vectors["joints"] = "edge_vectors";
  check_message(setup_error(edge_vectors),
                {"c.json: supports[0].fix[0]: \"opening_angle\": edge-vector joints"});
  // At a rotation joint it applies.
  const Config fine = parse(with("/supports", {{{"vertex", 2}, {"fix", {"opening_angle"}}}}));
  CHECK(make_problem_setup(fine, graph).statics.supports.size() == 1);
}

TEST_CASE("config: read_config refuses a FIFO or a device or an oversized file at once") {
  namespace fs = std::filesystem;
  const ScratchDirectory scratch("config-kinds");
  const fs::path& dir = scratch.path();
  REQUIRE(::mkfifo((dir / "fifo.json").c_str(), 0600) == 0);
  auto reading = std::async(std::launch::async, [&]() -> std::string {
    try {
      read_config((dir / "fifo.json").string());
    } catch (const InputError& e) {
      return e.what();
    }
    return "(read)";
  });
  if (reading.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    FAIL_CHECK("reading a FIFO blocked");
    std::ofstream(dir / "fifo.json") << "";  // the writer the reader waits for
  }
  CHECK(reading.get() == "cannot open configuration file '" + (dir / "fifo.json").string() +
                             "': it is a FIFO (named pipe), not a regular file");
  CHECK_THROWS_WITH_AS(read_config("/dev/zero"),
                       "cannot open configuration file '/dev/zero': it is a device, not a regular "
                       "file",
                       InputError);
  { std::ofstream(dir / "huge.json") << ""; }
  fs::resize_file(dir / "huge.json", std::uintmax_t{257} << 20);  // sparse: no disk
  CHECK_THROWS_WITH_AS(read_config((dir / "huge.json").string()),
                       doctest::Contains("a configuration file may have at most 268435456"),
                       InputError);
}

}  // namespace xshell::test
