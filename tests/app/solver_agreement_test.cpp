// The command's solvers reach the same equilibrium of the bundled sample:
// vertices within 1e-6 of the bounding-box diagonal, opening angles within
// 1e-6 rad, energies within 1e-7 relative, at gradient tolerance 1e-8.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "app/command_runner.hpp"

namespace xshell::test {

namespace {

nlohmann::json solve_sample(const fs::path& dir, const std::string& solver) {
  write_text(dir / (solver + ".json"),
             sample_config(dir / solver, R"(, "solver": {"gradient_tolerance": 1e-8})"));
  const CommandResult r =
      run_xshell("relax " + solver + ".json --solver " + solver + " --quiet", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  nlohmann::json s = read_json(dir / solver / "summary.json");
  CHECK(s["solver"] == solver);
  CHECK(s["converged"] == true);
  CHECK(s["stable"] == true);
  CHECK(s["gradient_norm"].get<double>() <= 1e-8);
  return s;
}

double bounding_box_diagonal(const nlohmann::json& vertices) {
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const auto& v : vertices)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], v[c].get<double>());
      hi[c] = std::max(hi[c], v[c].get<double>());
    }
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

void check_same_equilibrium(const nlohmann::json& a, const nlohmann::json& b) {
  const double diagonal = bounding_box_diagonal(a["vertices"]);
  REQUIRE(a["vertices"].size() == b["vertices"].size());
  double vertex_error = 0.0, angle_error = 0.0;
  for (size_t v = 0; v < a["vertices"].size(); ++v) {
    for (int c = 0; c < 3; ++c)
      vertex_error = std::max(vertex_error, std::abs(a["vertices"][v][c].get<double>() -
                                                     b["vertices"][v][c].get<double>()));
    if (!a["opening_angles"][v].is_null())
      angle_error = std::max(angle_error, std::abs(a["opening_angles"][v].get<double>() -
                                                   b["opening_angles"][v].get<double>()));
  }
  const double ea = a["energy"]["total"].get<double>(), eb = b["energy"]["total"].get<double>();
  MESSAGE("vertices " << vertex_error / diagonal << " of the diagonal, angles " << angle_error
                      << " rad, energies " << std::abs(ea - eb) / std::abs(ea) << " relative");
  CHECK(vertex_error <= 1e-6 * diagonal);
  CHECK(angle_error <= 1e-6);
  CHECK(std::abs(ea - eb) <= 1e-7 * std::abs(ea));
}

}  // namespace

TEST_CASE("relax: kinetic damping reaches Newton's equilibrium of the sample") {
  const ScratchDirectory scratch("agreement_kinetic");
  const fs::path& dir = scratch.path();
  const nlohmann::json newton = solve_sample(dir, "newton");
  const nlohmann::json kinetic = solve_sample(dir, "kinetic-damping");
  CHECK(kinetic["iterations"].get<long>() > newton["iterations"].get<long>());
  // The series holds the resets, not every leapfrog iteration.
  CHECK(kinetic["history"].size() < kinetic["iterations"].get<size_t>() / 10);
  check_same_equilibrium(newton, kinetic);
}

TEST_CASE("relax: damped dynamics reaches Newton's equilibrium of the sample, in both forms") {
  const ScratchDirectory scratch("agreement_dynamics");
  const fs::path& dir = scratch.path();
  const nlohmann::json newton = solve_sample(dir, "newton");
  const nlohmann::json second = solve_sample(dir, "dynamics");
  CHECK(second["simulated_time"].get<double>() > 0.0);
  check_same_equilibrium(newton, second);
  // The overdamped flow, through the configuration.
  write_text(
      dir / "first.json",
      sample_config(
          dir / "first",
          R"(, "solver": {"method": "dynamics", "first_order": true, "gradient_tolerance": 1e-8})"));
  const CommandResult r = run_xshell("relax first.json --quiet", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json first = read_json(dir / "first" / "summary.json");
  CHECK(first["converged"] == true);
  check_same_equilibrium(newton, first);
}

}  // namespace xshell::test
