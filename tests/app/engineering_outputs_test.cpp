// `xshell relax` end to end: the engineering results in summary.json and
// their VTK files, with the reactions checked against the loads.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "command_runner.hpp"
#include "io/obj_reader.hpp"
#include "linkage/topology.hpp"

namespace xshell::test {

using nlohmann::json;

namespace {

const double kDensity = 1800, kWidth = 0.01, kHeight = 0.007, kGravity = 9.81, kPointLoad = 5.0;

LineGraph sample_graph() { return read_obj((fs::path(XSHELL_SAMPLES_DIR) / "grid.obj").string()); }

double edge_length(const LineGraph& g, int e) {
  return (g.vertices[g.edges[e][1]] - g.vertices[g.edges[e][0]]).norm();
}

// The sample's configuration with a strength and a tight tolerance (1e-8, 100
// times the default, above the round-off floor) so that the reactions balance the loads closely.
json engineering_config(const fs::path& out) {
  json c = json::parse(sample_config(out));
  c["material"]["strength"] = 3.0e7;
  c["solver"] = {{"gradient_tolerance", 1e-8}};
  return c;
}

// Sum of the z components of every reaction in the summary.
Eigen::Vector3d reaction_sum(const json& summary) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const json& r : summary["reactions"])
    for (int c = 0; c < 3; ++c) sum[c] += r["force"][c].get<double>();
  return sum;
}

}  // namespace

TEST_CASE(
    "relax: summary.json reports reactions, stresses, joint forces and stability, the VTK files "
    "exist") {
  const ScratchDirectory scratch("engineering");
  const fs::path& dir = scratch.path();
  write_text(dir / "run.json", engineering_config(dir / "out").dump(2));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const json s = read_json(dir / "out" / "summary.json");
  REQUIRE(s["converged"] == true);

  // Reactions: one per support, and together they carry the weight (density
  // x area x total rod length x g) and the point load.
  REQUIRE(s["reactions"].is_array());
  CHECK(s["reactions"].size() == 4);
  const LineGraph graph = sample_graph();
  double length = 0.0;
  for (size_t e = 0; e < graph.edges.size(); ++e) length += edge_length(graph, static_cast<int>(e));
  CHECK(length > 1.0);
  const double weight = kDensity * kWidth * kHeight * length * kGravity;
  const Eigen::Vector3d sum = reaction_sum(s);
  CHECK(sum.z() == doctest::Approx(weight + kPointLoad).epsilon(1e-6));
  CHECK(std::abs(sum.x()) <= 1e-6 * sum.z());
  CHECK(std::abs(sum.y()) <= 1e-6 * sum.z());
  for (const json& reaction : s["reactions"]) {
    CHECK(reaction["moment"].is_null());  // pins: no orientation fixed
    CHECK(reaction["position"].size() == 3);
  }

  // Stresses, with the utilisation of the given strength.
  REQUIRE(s["stresses"].is_object());
  for (const char* key :
       {"max_normal_stress", "max_torsional_shear", "max_axial_force", "max_utilisation"}) {
    CAPTURE(key);
    REQUIRE(s["stresses"][key].is_object());
    CHECK(s["stresses"][key]["value"].is_number());
    CHECK(s["stresses"][key]["rod"].get<int>() >= 0);
  }
  const double sigma = s["stresses"]["max_normal_stress"]["value"].get<double>();
  CHECK(sigma > 0.0);
  // The equivalent stress is at least the normal stress.
  CHECK(s["stresses"]["max_utilisation"]["value"].get<double>() >= sigma / 3.0e7 * (1 - 1e-12));

  // Joint forces: one entry per joint (vertices of valence 2 to 4).
  REQUIRE(s["joint_forces"].is_array());
  int joints = 0;
  std::vector<int> valence(graph.vertices.size(), 0);
  for (const auto& e : graph.edges) ++valence[e[0]], ++valence[e[1]];
  for (int v : valence) joints += v >= 2;
  CHECK(s["joint_forces"].size() == static_cast<size_t>(joints));
  CHECK(s["joint_forces"][0]["force_on_a"].size() == 3);

  // Stability.
  REQUIRE(s["lowest_eigenvalues"].is_array());
  CHECK(s["lowest_eigenvalues"].size() == 6);
  CHECK(s["lowest_eigenvalues"][0].get<double>() > 0.0);  // stable, held in place
  CHECK(s.contains("buckling_load_factor"));
  CHECK((s["buckling_load_factor"].is_null() || s["buckling_load_factor"].get<double>() > 0.0));
  CHECK(s["stability_analysis"]["eigenvalues"] == "converged");

  for (const char* file : {"reactions.vtp", "stresses.vtp", "joint_forces.vtp", "modes.vtp"}) {
    CAPTURE(file);
    CHECK(fs::exists(dir / "out" / file));
    CHECK(fs::file_size(dir / "out" / file) > 0);
  }
  fs::remove_all(dir);
}

TEST_CASE("relax: a heavier, wider rod and a settled support show in the reactions and positions") {
  // Rod 0 gets twice the density and a wider section ("rods"); vertex 1's
  // pin settles by 2 mm ("displacement").
  const LineGraph graph = sample_graph();
  const LinkageTopology topology = build_topology(graph);
  double rod0 = 0.0, others = 0.0;
  for (size_t e = 0; e < graph.edges.size(); ++e)
    (topology.segments[e].rod == 0 ? rod0 : others) += edge_length(graph, static_cast<int>(e));
  REQUIRE(rod0 > 0.0);

  const ScratchDirectory scratch("engineering-mixed");
  const fs::path& dir = scratch.path();
  json c = engineering_config(dir / "out");
  c["rods"] = {
      {{"rod", 0},
       {"material", {{"density", 2 * kDensity}, {"cross_section", {{"width", 2 * kWidth}}}}}}};
  c["supports"][0]["displacement"] = {0, 0, -0.002};
  REQUIRE(c["supports"][0]["vertex"] == 1);
  write_text(dir / "run.json", c.dump(2));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const json s = read_json(dir / "out" / "summary.json");
  REQUIRE(s["converged"] == true);
  const double weight =
      kDensity * kHeight * kGravity * (others * kWidth + rod0 * 2.0 * kWidth * 2.0);
  CHECK(reaction_sum(s).z() == doctest::Approx(weight + kPointLoad).epsilon(1e-6));
  // The settled pin sits (and its reaction acts) at input + displacement.
  CHECK(s["vertices"][1][2].get<double>() == doctest::Approx(-0.002).epsilon(1e-12));
  CHECK(s["reactions"][0]["vertex"] == 1);
  CHECK(s["reactions"][0]["position"][2].get<double>() == doctest::Approx(-0.002).epsilon(1e-12));
  CHECK(s["configuration"]["rods"][0]["material"]["cross_section"]["height"] == kHeight);
  CHECK(s["configuration"]["supports"][0]["displacement"][2] == -0.002);
  fs::remove_all(dir);
}

TEST_CASE(
    "relax: a cantilever clamped at its vertex bends as the elastica and its clamp balances the "
    "load") {
  // A rod of length 1 along x, E I = 1 (square section, side 0.01), clamped
  // at vertex 0 with "fix": ["position", "orientation"], tip load P L^2 / E I
  // = 2 along -z: the elastica's tip deflection is 0.49346 L; with 100 edges
  // the clamp at the vertex comes within 1e-4 L of it (second order).
  const ScratchDirectory scratch("engineering-clamp");
  const fs::path& dir = scratch.path();
  write_text(dir / "rod.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  const json c = {
      {"linkage", (dir / "rod.obj").string()},
      {"subdivisions", 100},
      {"rest_shape", "straight"},
      {"material",
       {{"young_modulus", 1.2e9},
        {"cross_section", {{"shape", "rectangle"}, {"width", 0.01}, {"height", 0.01}}}}},
      {"supports", {{{"vertex", 0}, {"fix", {"position", "orientation"}}}}},
      {"loads", {{"forces", {{{"vertex", 1}, {"force", {0, 0, -2.0}}}}}}},
      {"solver", {{"gradient_tolerance", 1e-8}}},
      {"output", {{"directory", (dir / "out").string()}}}};
  write_text(dir / "run.json", c.dump(2));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const json s = read_json(dir / "out" / "summary.json");
  REQUIRE(s["converged"] == true);
  auto vec = [](const json& j) {
    return Eigen::Vector3d(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  };
  const Eigen::Vector3d root = vec(s["vertices"][0]), tip = vec(s["vertices"][1]);
  CHECK(root.norm() <= 1e-12);  // the clamp holds its vertex in place
  CHECK(std::abs(-tip.z() - 0.49346) <= 1e-4);
  // The clamp's reaction: -P, and about the vertex the load's moment with
  // the deflected lever, (tip - root) x P + M = 0.
  REQUIRE(s["reactions"].size() == 1);
  const json& reaction = s["reactions"][0];
  const Eigen::Vector3d load(0, 0, -2.0);
  const Eigen::Vector3d force = vec(reaction["force"]);
  REQUIRE(reaction["moment"].is_array());
  const Eigen::Vector3d moment = vec(reaction["moment"]);
  CHECK((force + load).norm() <= 1e-6 * load.norm());
  CHECK((moment + (tip - root).cross(load)).norm() <= 1e-6 * load.norm());
  fs::remove_all(dir);
}

TEST_CASE("relax: a rods entry or a displacement that does not apply exits 2 naming the key") {
  const ScratchDirectory scratch("engineering-bad");
  const fs::path& dir = scratch.path();
  json c = engineering_config(dir / "out");
  c["rods"] = {{{"rod", 99}, {"material", {{"density", 1}}}}};
  write_text(dir / "run.json", c.dump(2));
  CommandResult r = run_xshell("relax run.json", dir);
  CHECK(r.status == 2);
  CHECK(r.errors.find("rods[0].rod: rod 99 is out of range") != std::string::npos);
  c.erase("rods");
  c["supports"][0]["fix"] = {"z"};
  c["supports"][0]["displacement"] = {0.001, 0, 0};
  write_text(dir / "run.json", c.dump(2));
  r = run_xshell("relax run.json", dir);
  CHECK(r.status == 2);
  CHECK(r.errors.find("supports[0].displacement[0]: moves the x component") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out" / "summary.json"));
  fs::remove_all(dir);
}

}  // namespace xshell::test
