// Validation on the real designs (../shared/data/elasticrods; skipped when
// absent): flat linkages deployed past the angle where their flat state
// loses stability leave it on the side of solver.buckling_direction, and
// every step is a stable equilibrium (README, "Saddles and the branch").
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "command_runner.hpp"
#include "skip.hpp"

namespace xshell::test {

namespace {

const fs::path kData = XSHELL_SHARED_DATA_DIR;

// Straight laths 10 x 7 mm, E = 20000, no supports (the centre joint is
// pinned), 8 edges per segment.
nlohmann::json design_config(const std::string& obj, const nlohmann::json& deployment,
                             const nlohmann::json& solver) {
  return {{"linkage", (kData / obj).string()},
          {"subdivisions", 8},
          {"rest_shape", "straight"},
          {"material",
           {{"young_modulus", 20000},
            {"cross_section", {{"shape", "rectangle"}, {"width", 10}, {"height", 7}}}}},
          {"solver", solver},
          {"deployment", deployment},
          {"output", {{"directory", "out"}, {"solids", false}, {"every", 1000}}}};
}

struct Deployed {
  nlohmann::json summary;
  std::vector<std::string> stable;  // deployment.csv's column, per step
  double mean_z = 0.0;              // of the vertices, at the end
};

// deployment.csv's last column ("stable"), per step.
std::vector<std::string> stable_column(const fs::path& csv) {
  const std::string table = read_text(csv);
  const auto fields = [](const std::string& row) {
    std::vector<std::string> out;
    for (size_t start = 0;;) {
      const size_t comma = row.find(',', start);
      out.push_back(row.substr(start, comma - start));
      if (comma == std::string::npos) return out;
      start = comma + 1;
    }
  };
  const std::vector<std::string> header = fields(table.substr(0, table.find('\n')));
  const size_t column = std::find(header.begin(), header.end(), "stable") - header.begin();
  REQUIRE(column < header.size());
  std::vector<std::string> out;
  size_t start = table.find('\n') + 1;
  while (start < table.size()) {
    const size_t end = table.find('\n', start);
    out.push_back(fields(table.substr(start, end - start)).at(column));
    start = end + 1;
  }
  return out;
}

Deployed deploy(const fs::path& dir, const nlohmann::json& config) {
  write_text(dir / "run.json", config.dump(2));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  Deployed d;
  d.summary = read_json(dir / "out" / "summary.json");
  d.stable = stable_column(dir / "out" / "deployment.csv");
  const nlohmann::json& vertices = d.summary["vertices"];
  for (const auto& v : vertices) d.mean_z += v[2].get<double>() / vertices.size();
  return d;
}

void check_every_step_stable(const Deployed& d, size_t steps) {
  CHECK(d.summary["deployment"]["status"] == "completed");
  CHECK(d.summary["stable"] == true);
  REQUIRE(d.stable.size() == steps + 1);
  int unstable = 0;
  for (const std::string& s : d.stable) unstable += s == "true" ? 0 : 1;
  CHECK(unstable == 0);
}

// The largest distance between the two runs' final vertices (mm).
double largest_vertex_distance(const Deployed& a, const Deployed& b) {
  double largest = 0.0;
  for (size_t v = 0; v < a.summary["vertices"].size(); ++v) {
    double squared = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d =
          a.summary["vertices"][v][k].get<double>() - b.summary["vertices"][v][k].get<double>();
      squared += d * d;
    }
    largest = std::max(largest, std::sqrt(squared));
  }
  return largest;
}

// Gravity along -z on steel laths (t/mm^3, mm/s^2): against the default
// buckling direction.
nlohmann::json with_gravity(nlohmann::json config) {
  config["material"]["density"] = 7.85e-9;
  config["loads"] = {{"gravity", {0, 0, -9810}}};
  return config;
}

}  // namespace

TEST_CASE("manta ray deployed to 93 degrees leaves the flat state up (or down when asked)" *
          doctest::test_suite("validation")) {
  if (!fs::exists(kData / "manta_ray_5ca2f7ab.obj"))
    XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  const nlohmann::json deployment = {{"average_opening_angle", 93.0 * M_PI / 180.0}, {"steps", 20}};
  const ScratchDirectory scratch("manta_branch");
  const fs::path& dir = scratch.path();
  const Deployed up =
      deploy(dir, design_config("manta_ray_5ca2f7ab.obj", deployment, nlohmann::json::object()));
  check_every_step_stable(up, 20);
  REQUIRE(up.summary["saddles_escaped"].size() >= 1);
  CHECK(up.summary["saddles_escaped"][0]["lowest_eigenvalue"].get<double>() < 0.0);
  CHECK(up.summary["saddles_escaped"][0]["step"].get<int>() > 0);
  CHECK(up.mean_z > 10.0);  // mm: the shell rose (the flat start has mean z 0)
  const Deployed down = deploy(dir, design_config("manta_ray_5ca2f7ab.obj", deployment,
                                                  {{"buckling_direction", {0, 0, -1}}}));
  check_every_step_stable(down, 20);
  CHECK(down.mean_z == doctest::Approx(-up.mean_z).epsilon(1e-6));  // the mirror image
  CHECK(down.summary["energy"]["total"].get<double>() ==
        doctest::Approx(up.summary["energy"]["total"].get<double>()).epsilon(1e-9));
  MESSAGE("manta ray to 93 deg: mean z " << up.mean_z << " mm up, " << down.mean_z << " mm down; "
                                         << up.summary["iterations"] << " Newton iterations");
}

TEST_CASE("manta ray deployed by damped dynamics reaches Newton's branch" *
          doctest::test_suite("validation")) {
  if (!fs::exists(kData / "manta_ray_5ca2f7ab.obj"))
    XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  const nlohmann::json deployment = {{"average_opening_angle", 93.0 * M_PI / 180.0}, {"steps", 20}};
  const ScratchDirectory scratch("manta_dynamics");
  const fs::path& dir = scratch.path();
  const Deployed newton =
      deploy(dir, design_config("manta_ray_5ca2f7ab.obj", deployment, nlohmann::json::object()));
  const Deployed dynamics =
      deploy(dir, design_config("manta_ray_5ca2f7ab.obj", deployment, {{"method", "dynamics"}}));
  check_every_step_stable(dynamics, 20);
  REQUIRE(dynamics.summary["saddles_escaped"].size() == newton.summary["saddles_escaped"].size());
  CHECK(dynamics.summary["saddles_escaped"][0]["step"] ==
        newton.summary["saddles_escaped"][0]["step"]);
  const double largest = largest_vertex_distance(newton, dynamics);
  CHECK(largest < 1e-4);
  CHECK(dynamics.mean_z > 10.0);
  MESSAGE("manta ray to 93 deg, dynamics against Newton: largest vertex distance " << largest
                                                                                   << " mm");
}

TEST_CASE("darth vader opened at two joints to 2 rad leaves the flat state up and stays stable" *
          doctest::test_suite("validation")) {
  if (!fs::exists(kData / "darth_vader_fig5_1693d9a2.obj"))
    XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  const nlohmann::json deployment = {
      {"joint_angles", {{{"vertex", 19}, {"angle", 2.0}}, {{"vertex", 60}, {"angle", 2.0}}}},
      {"steps", 20}};
  const ScratchDirectory scratch("darth_branch");
  const fs::path& dir = scratch.path();
  const Deployed up = deploy(
      dir, design_config("darth_vader_fig5_1693d9a2.obj", deployment, nlohmann::json::object()));
  check_every_step_stable(up, 20);
  CHECK(up.summary["saddles_escaped"].size() >= 1);
  CHECK(up.mean_z > 1.0);
  MESSAGE("darth vader, joints 19 and 60 to 2 rad: mean z "
          << up.mean_z << " mm; " << up.summary["iterations"] << " Newton iterations");
}

TEST_CASE("manta ray under gravity deployed to 93 degrees takes the branch the user chose" *
          doctest::test_suite("validation")) {
  if (!fs::exists(kData / "manta_ray_5ca2f7ab.obj"))
    XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  const nlohmann::json deployment = {{"average_opening_angle", 93.0 * M_PI / 180.0}, {"steps", 20}};
  const ScratchDirectory scratch("manta_gravity");
  const fs::path& dir = scratch.path();
  const Deployed up = deploy(dir, with_gravity(design_config("manta_ray_5ca2f7ab.obj", deployment,
                                                             nlohmann::json::object())));
  check_every_step_stable(up, 20);
  CHECK(up.summary["deployment"]["branch_switch_step"].is_number_integer());
  CHECK(up.mean_z > 10.0);  // mm: up, against gravity
  const Deployed down =
      deploy(dir, with_gravity(design_config("manta_ray_5ca2f7ab.obj", deployment,
                                             {{"buckling_direction", {0, 0, -1}}})));
  check_every_step_stable(down, 20);
  CHECK(down.summary["deployment"]["branch_switch_step"].is_null());
  CHECK(down.mean_z < -10.0);
  // Gravity favours the lower branch.
  CHECK(down.summary["energy"]["total"].get<double>() <
        up.summary["energy"]["total"].get<double>());
  MESSAGE("manta ray under gravity to 93 deg: mean z "
          << up.mean_z << " mm up (switched at step "
          << up.summary["deployment"]["branch_switch_step"] << "), " << down.mean_z << " mm down");
}

TEST_CASE("manta ray under gravity deployed by damped dynamics reaches Newton's branch" *
          doctest::test_suite("validation")) {
  if (!fs::exists(kData / "manta_ray_5ca2f7ab.obj"))
    XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  const nlohmann::json deployment = {{"average_opening_angle", 93.0 * M_PI / 180.0}, {"steps", 20}};
  const ScratchDirectory scratch("manta_gravity_dynamics");
  const fs::path& dir = scratch.path();
  const Deployed newton = deploy(
      dir,
      with_gravity(design_config("manta_ray_5ca2f7ab.obj", deployment, nlohmann::json::object())));
  const Deployed dynamics = deploy(
      dir,
      with_gravity(design_config("manta_ray_5ca2f7ab.obj", deployment, {{"method", "dynamics"}})));
  check_every_step_stable(dynamics, 20);
  CHECK(dynamics.summary["deployment"]["branch_switch_step"] ==
        newton.summary["deployment"]["branch_switch_step"]);
  const double largest = largest_vertex_distance(newton, dynamics);
  CHECK(largest < 1e-3);
  CHECK(dynamics.mean_z > 10.0);
  MESSAGE("manta ray under gravity, dynamics against Newton: largest vertex distance " << largest
                                                                                       << " mm");
}

TEST_CASE("darth vader deployed to 115 degrees with and without gravity leaves the plane upwards" *
          doctest::test_suite("validation")) {
  if (!fs::exists(kData / "darth_vader_fig5_1693d9a2.obj"))
    XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  const nlohmann::json deployment = {{"average_opening_angle", 115.0 * M_PI / 180.0},
                                     {"steps", 20}};
  const ScratchDirectory scratch("darth_average");
  const fs::path& dir = scratch.path();
  const nlohmann::json plain =
      design_config("darth_vader_fig5_1693d9a2.obj", deployment, nlohmann::json::object());
  const Deployed free = deploy(dir, plain);
  check_every_step_stable(free, 20);
  CHECK(free.summary["saddles_escaped"].size() >= 1);
  CHECK(free.mean_z > 10.0);
  const Deployed loaded = deploy(dir, with_gravity(plain));
  check_every_step_stable(loaded, 20);
  CHECK(loaded.summary["deployment"]["branch_switch_step"].is_number_integer());
  CHECK(loaded.mean_z > 10.0);
  MESSAGE("darth vader to 115 deg: mean z " << free.mean_z << " mm without gravity, "
                                            << loaded.mean_z << " mm with");
}

// The largest design relaxed from flat (no supports: the centre joint
// pinned) first converges to a flat saddle, then reaches a stable state from
// which a deployment by +0.3 rad is stable at every step; with the default
// settings (Newton's iteration limit included) at 8 and at 10 subdivisions.
namespace {

void relax_and_deploy_largest(int subdivisions) {
  if (!fs::exists(kData / "large_6d35a972.obj")) XSHELL_SKIP(XSHELL_SHARED_DATA_DIR " is absent");
  const ScratchDirectory scratch("largest_saddle");
  const fs::path& dir = scratch.path();
  nlohmann::json config = design_config("large_6d35a972.obj", nullptr, nlohmann::json::object());
  config.erase("deployment");
  config["subdivisions"] = subdivisions;
  write_text(dir / "relax.json", config.dump(2));
  const CommandResult relaxed = run_xshell("relax relax.json --out relaxed", dir);
  CAPTURE(relaxed.errors);
  REQUIRE(relaxed.status == 0);
  const nlohmann::json s = read_json(dir / "relaxed" / "summary.json");
  CHECK(s["stable"] == true);
  REQUIRE(s["saddles_escaped"].size() >= 1);
  CHECK(s["saddles_escaped"][0]["lowest_eigenvalue"].get<double>() < 0.0);
  CHECK(s["energy"]["total"].get<double>() < s["saddles_escaped"][0]["energy"].get<double>());
  double average = 0.0;
  int joints = 0;
  for (const auto& a : s["opening_angles"])
    if (!a.is_null()) average += a.get<double>(), ++joints;
  average /= joints;
  config["deployment"] = {{"average_opening_angle", average + 0.3}, {"steps", 10}};
  write_text(dir / "deploy.json", config.dump(2));
  const CommandResult deployed =
      run_xshell("relax deploy.json --init relaxed/state.json --out deployed", dir);
  CAPTURE(deployed.errors);
  REQUIRE(deployed.status == 0);
  Deployed d;
  d.summary = read_json(dir / "deployed" / "summary.json");
  d.stable = stable_column(dir / "deployed" / "deployment.csv");
  check_every_step_stable(d, 10);
  MESSAGE("largest design, n_s = "
          << subdivisions << ": saddle " << s["saddles_escaped"][0]["energy"] << ", stable "
          << s["energy"]["total"] << " after " << s["iterations"] << " iterations");
}

}  // namespace

TEST_CASE("largest design: relaxed past its flat saddle and then deployed by 0.3 rad" *
          doctest::test_suite("validation")) {
  relax_and_deploy_largest(8);
}

TEST_CASE(
    "largest design at 10 subdivisions: relaxed past its flat saddle and deployed by 0.3 rad" *
    doctest::test_suite("validation")) {
  relax_and_deploy_largest(10);
}

}  // namespace xshell::test
