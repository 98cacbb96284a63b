// `xshell design` end to end (README, "Design"): a shape recovered from its
// own deployed joints, a target surface, and inputs refused with status 2.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <sstream>

#include "command_runner.hpp"
#include "linkage/bounding_box.hpp"

namespace xshell::test {

namespace {

// An n x n grid (spacing 0.25, centred) lifted onto the dome z = -k r^2,
// stress-free as drawn: a curved linkage that deploys out of its plane.
std::string dome_obj(int n, double k) {
  std::ostringstream out;
  out.precision(17);
  const double half = 0.5 * (n - 1) * 0.25;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -half + 0.25 * j, y = -half + 0.25 * i;
      out << "v " << x << ' ' << y << ' ' << -k * (x * x + y * y) << '\n';
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * n + j + 1;
      if (j + 1 < n) out << "l " << v << ' ' << v + 1 << '\n';
      if (i + 1 < n) out << "l " << v << ' ' << v + n << '\n';
    }
  return out.str();
}

// The paraboloid z = -k r^2 over [-L, L]^2 as an m x m triangle mesh.
std::string paraboloid_obj(int m, double L, double k) {
  std::ostringstream out;
  out.precision(17);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double x = -L + 2 * L * j / (m - 1), y = -L + 2 * L * i / (m - 1);
      out << "v " << x << ' ' << y << ' ' << -k * (x * x + y * y) << '\n';
    }
  for (int i = 0; i + 1 < m; ++i)
    for (int j = 0; j + 1 < m; ++j) {
      const int a = i * m + j + 1, b = a + 1, c = a + m, d = c + 1;
      out << "f " << a << ' ' << b << ' ' << d << "\nf " << a << ' ' << d << ' ' << c << '\n';
    }
  return out.str();
}

// The dome's configuration (centre joint of an odd grid, or joint 5, held),
// with `extra` keys appended.
std::string dome_config(int n, const std::string& extra) {
  const int held = n % 2 ? (n * n) / 2 : n + 1;
  return R"({"linkage": "dome.obj", "subdivisions": 5, "rest_shape": "input",
  "material": {"young_modulus": 2e10, "cross_section": {"width": 0.01, "height": 0.007}},
  "supports": [{"vertex": )" +
         std::to_string(held) + R"(, "fix": ["position", "orientation"]}],
  "output": {"directory": "out", "solids": false})" +
         extra + "}";
}

double bounding_diagonal(const nlohmann::json& vertices) {
  BoundingBox box;
  for (const auto& v : vertices)
    box.extend(Eigen::Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>()));
  return box.diagonal().norm();
}

}  // namespace

TEST_CASE("design: rest lengths perturbed by up to 5% are recovered from their deployed joints") {
  const ScratchDirectory scratch("design-recovery");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj(3, 0.8));
  // The "true" design: every rest length perturbed, deployed by relax.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> factor(0.95, 1.05);
  nlohmann::json lengths = nlohmann::json::array();
  for (int s = 0; s < 12; ++s) lengths.push_back(0.25 * factor(rng));
  const double angle = 1.85;
  write_text(dir / "truth.json", dome_config(3, R"(, "rest_lengths": )" + lengths.dump() +
                                                    R"(, "solver": {"gradient_tolerance": 1e-10},
  "deployment": {"average_opening_angle": )" + std::to_string(angle) +
                                                    R"(, "steps": 10}, "analysis": {"modes": 0})"));
  const CommandResult truth = run_xshell("relax truth.json --out truth --quiet", dir);
  CAPTURE(truth.errors);
  REQUIRE(truth.status == 0);
  const nlohmann::json vertices = read_json(dir / "truth" / "summary.json")["vertices"];
  write_text(dir / "target.json", nlohmann::json{{"positions", vertices}}.dump());
  // The design from the drawing's rest lengths (the segments' 0.25 along
  // the dome) toward those joints.
  write_text(dir / "design.json",
             dome_config(3, R"(, "solver": {"gradient_tolerance": 1e-10},
  "design": {"average_opening_angle": )" +
                                std::to_string(angle) +
                                R"(, "target_joints": "target.json", "max_iterations": 200})"));
  const CommandResult r = run_xshell("design design.json", dir);
  CAPTURE(r.errors);
  CHECK(r.status == 0);
  const nlohmann::json d = read_json(dir / "out" / "design.json");
  CHECK(d["status"] == "converged");
  CHECK(d["fit"]["targets"] == 9);
  const double diagonal = bounding_diagonal(vertices);
  CHECK(d["fit"]["max"].get<double>() <= 1e-4 * diagonal);
  const nlohmann::json& history = d["history"];
  REQUIRE(history.size() >= 2);
  CHECK(history.front()["objective"].get<double>() >=
        1e4 * history.back()["objective"].get<double>());
  CHECK(d["rest_lengths"].size() == 12);
  CHECK(d["iterations"].get<int>() == static_cast<int>(history.size()) - 1);
  // One progress line per design iteration.
  int lines = 0;
  for (std::size_t p = r.errors.find("xshell: design: iteration "); p != std::string::npos;
       p = r.errors.find("xshell: design: iteration ", p + 1))
    ++lines;
  CHECK(lines == static_cast<int>(history.size()));
  // The optimized flat state, relaxed with the design's rest lengths, is an
  // equilibrium that deploys to the target: relax it with those lengths.
  for (const char* file : {"deployed_state.json", "flat_state.json", "flat_layout.obj",
                           "series.pvd", "fabrication.json", "joints_000001.vtp"})
    CHECK_MESSAGE(fs::exists(dir / "out" / file), file);
  // The deployed step has the array, the flat one not (its header names it;
  // the units table in the appended data lists every array's unit).
  const std::string array = "Name=\"target_distance\"";
  CHECK(read_text(dir / "out" / "joints_000001.vtp").find(array) != std::string::npos);
  CHECK(read_text(dir / "out" / "joints_000000.vtp").find(array) == std::string::npos);
}

TEST_CASE("design: a target surface attracts every joint, and the flat state stays flat") {
  const ScratchDirectory scratch("design-surface");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj(4, 0.8));
  write_text(dir / "surface.obj", paraboloid_obj(21, 0.8, 1.1));
  write_text(dir / "design.json", dome_config(4, R"(, "design": {"average_opening_angle": 1.9,
  "target_surface": "surface.obj", "max_iterations": 15, "weights": {"regularization": 0.01}})"));
  const CommandResult r = run_xshell("design design.json --out result", dir);
  CAPTURE(r.errors);
  CHECK((r.status == 0 || r.status == 3));
  const nlohmann::json d = read_json(dir / "result" / "design.json");
  CHECK(d["fit"]["targets"] == 16);  // every joint
  const nlohmann::json& history = d["history"];
  REQUIRE(history.size() >= 2);
  // The fit improves by more than a factor 3 within 15 iterations (0.0406 to
  // 0.0074 measured).
  CHECK(history.back()["fit_rms"].get<double>() < history.front()["fit_rms"].get<double>() / 3);
  CHECK(d["fit"]["rms"].get<double>() == doctest::Approx(history.back()["fit_rms"].get<double>()));
  // The dome is not flat: nothing is held in a plane.
  CHECK(d["flat"]["held_planar"] == false);
  // Every rest length within the default bounds (20%).
  for (std::size_t s = 0; s < d["rest_lengths"].size(); ++s) {
    const double p = d["rest_lengths"][s], p0 = d["start_rest_lengths"][s];
    CHECK(std::abs(p / p0 - 1) <= 0.2 + 1e-9);
  }
}

TEST_CASE("design: a flat linkage's flat state is held in its plane") {
  const ScratchDirectory scratch("design-planar");
  const fs::path& dir = scratch.path();
  // The bundled flat grid of straight laths, pulled toward a smaller copy
  // of itself lifted by 0.05, with its flat energy weighed in.
  const std::string obj = (fs::path(XSHELL_SAMPLES_DIR) / "grid.obj").string();
  nlohmann::json positions = nlohmann::json::array();
  std::istringstream lines(read_text(obj));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      double x, y, z;
      v >> x >> y >> z;
      positions.push_back({0.9 * x, 0.9 * y, 0.05});
    }
  write_text(dir / "target.json", nlohmann::json{{"positions", positions}}.dump());
  write_text(dir / "design.json", R"({"linkage": ")" + obj + R"(", "subdivisions": 5,
  "rest_shape": "straight",
  "material": {"young_modulus": 2e10, "cross_section": {"width": 0.01, "height": 0.007}},
  "output": {"directory": "out", "solids": false},
  "design": {"average_opening_angle": 1.3, "target_joints": "target.json", "max_iterations": 3,
             "weights": {"flat_energy": 1}}})");
  const CommandResult r = run_xshell("design design.json", dir);
  CAPTURE(r.errors);
  CHECK((r.status == 0 || r.status == 3));
  const nlohmann::json d = read_json(dir / "out" / "design.json");
  CHECK(d["flat"]["held_planar"] == true);
  CHECK(d["flat"]["planarity"].get<double>() <= 1e-12);
  CHECK(d["history"].size() == 4);
  // The layout: the OBJ's 32 vertices, all at z = 0, and its 40 edges.
  std::istringstream layout(read_text(dir / "out" / "flat_layout.obj"));
  int vertices = 0, edges = 0;
  for (std::string line; std::getline(layout, line);) {
    std::istringstream in(line);
    std::string kind;
    in >> kind;
    if (kind == "v") {
      double x, y, z;
      in >> x >> y >> z;
      CHECK(std::abs(z) <= 1e-12);
      ++vertices;
    }
    if (kind == "l") ++edges;
  }
  CHECK(vertices == 32);
  CHECK(edges == 40);
}

TEST_CASE("design: bad design inputs are refused with status 2 and a clear message") {
  const ScratchDirectory scratch("design-bad");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj(3, 0.8));
  write_text(dir / "surface.obj", paraboloid_obj(5, 0.8, 1.0));
  write_text(dir / "short.json", R"({"positions": [[0, 0, 0]]})");
  const std::string angle = R"("average_opening_angle": 1.8)";
  struct Case {
    std::string extra, message;
  };
  for (const Case& c : std::vector<Case>{
           {"", "needs a \"design\" section"},
           {R"(, "design": {"target_surface": "surface.obj"})", "average_opening_angle"},
           {R"(, "design": {)" + angle + "}", "needs a target"},
           {R"(, "design": {)" + angle +
                R"(, "target_surface": "surface.obj", "target_joints": "short.json"})",
            "gives both"},
           {R"(, "design": {)" + angle + R"(, "target_joints": "short.json"})", "short.json"},
           {R"(, "design": {)" + angle + R"(, "target_joints": "missing.json"})", "missing.json"},
           {R"(, "design": {)" + angle + R"(, "target_surface": "dome.obj"})", "dome.obj"},
           {R"(, "design": {)" + angle + R"(, "target_surface": "surface.obj", "bounds": 1.5})",
            "design.bounds"},
           {R"(, "design": {)" + angle +
                R"(, "target_surface": "surface.obj", "weights": {"fit": 0}})",
            "every weight is 0"},
           {R"(, "design": {)" + angle +
                R"(, "target_surface": "surface.obj", "flat_planar": true})",
            "not flat"},
           {R"(, "design": {)" + angle + R"(, "target_surface": "surface.obj", "stepz": 3})",
            "steps"},
           {R"(, "loads": {"gravity": [0, 0, -9.81]}, "design": {)" + angle +
                R"(, "target_surface": "surface.obj"})",
            "gravity"},
       }) {
    CAPTURE(c.extra);
    write_text(dir / "design.json", dome_config(3, c.extra));
    const CommandResult r = run_xshell("design design.json", dir);
    CHECK(r.status == 2);
    CHECK(r.errors.find(c.message) != std::string::npos);
    CHECK(r.errors.find("xshell: error: ") == 0);
  }
  CHECK(run_xshell("design", dir).status == 2);
}

}  // namespace xshell::test
