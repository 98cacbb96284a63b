#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "app/deployment_plot.hpp"
#include "command_runner.hpp"
#include "skip.hpp"

namespace xshell::test {

namespace {

// A 3 x 3 grid of rods on a dome z = -0.8 (x^2 + y^2), spacing 0.25 m,
// stress-free as drawn; with `tail`, vertex 9 is a free end hanging off
// corner 0.
std::string dome_obj(bool tail = false) {
  std::ostringstream o;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double x = -0.25 + 0.25 * j, y = -0.25 + 0.25 * i;
      o << "v " << x << " " << y << " " << -0.8 * (x * x + y * y) << "\n";
    }
  if (tail) o << "v -0.5 -0.25 " << -0.8 * (0.25 + 0.0625) << "\n";
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int v = i * 3 + j + 1;  // 1-based
      if (j + 1 < 3) o << "l " << v << " " << v + 1 << "\n";
      if (i + 1 < 3) o << "l " << v << " " << v + 3 << "\n";
    }
  if (tail) o << "l 10 1\n";
  return o.str();
}

std::string deploy_config(const std::string& deployment, const std::string& solver = "newton") {
  return R"({
  "linkage": "dome.obj",
  "subdivisions": 5,
  "rest_shape": "input",
  "material": {"young_modulus": 2.0e10, "cross_section": {"shape": "rectangle", "width": 0.01, "height": 0.007}},
  "supports": [{"vertex": 4, "fix": ["position", "orientation"]}],
  "solver": {"method": ")" +
         solver + R"(", "gradient_tolerance": 1e-9, "first_order": true},
  "deployment": )" +
         deployment + R"(,
  "output": {"directory": "out", "solids": false}
})";
}

struct Table {
  std::string header;
  std::vector<std::vector<std::string>> rows;
};

Table read_table(const fs::path& path) {
  std::istringstream in(read_text(path));
  Table t;
  std::getline(in, t.header);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    t.rows.push_back(cells);
  }
  return t;
}

bool matplotlib_available() {
  for (const char* python : {"python3", "/usr/bin/python3"})
    if (std::system((std::string(python) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0)
      return true;
  return false;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("relax with a deployment: Newton's chord corrections in the summary and per iteration") {
  // The dome opened in 8 steps, some of which end with chord corrections:
  // the summary's count is the sum of those on the --verbose lines.
  const ScratchDirectory scratch("deploy-chords");
  write_text(scratch.path() / "dome.obj", dome_obj());
  write_text(scratch.path() / "run.json",
             deploy_config(R"({"average_opening_angle": 1.9, "steps": 8})", "newton"));
  const CommandResult r = run_xshell("relax run.json --verbose", scratch.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(scratch.path() / "out" / "summary.json");
  const long corrections = s["deployment"]["chord_corrections"].get<long>();
  long on_lines = 0;  // ", N chord correction(s)" after an iteration's factorizations
  for (size_t at = r.errors.find(" chord correction"); at != std::string::npos;
       at = r.errors.find(" chord correction", at + 1))
    on_lines += std::stol(r.errors.substr(r.errors.rfind(", ", at) + 2));
  CHECK(corrections >= 1);
  CHECK(on_lines == corrections);
}

TEST_CASE(
    "relax with a deployment: steps, deployment.csv, the VTK series, the plot and the summary") {
  int solvers = 0;
  for (const char* solver : {"newton", "dynamics"}) {
    CAPTURE(solver);
    const ScratchDirectory scratch("deploy");
    const fs::path& dir = scratch.path();
    write_text(dir / "dome.obj", dome_obj());
    write_text(dir / "run.json",
               deploy_config(R"({"average_opening_angle": 1.9, "steps": 4})", solver));
    const CommandResult r = run_xshell("relax run.json", dir);
    CAPTURE(r.errors);
    REQUIRE(r.status == 0);
    const Table t = read_table(dir / "out" / "deployment.csv");
    CHECK(t.header ==
          "step,average_angle,energy_total,energy_stretching,energy_bending,energy_twisting,torque,"
          "iterations,stable,min_opening_angle,max_opening_angle,factorizations");
    REQUIRE(t.rows.size() == 5);  // step 0 and 4 steps
    for (size_t k = 0; k < t.rows.size(); ++k) {
      REQUIRE(t.rows[k].size() == 12);
      CHECK(std::stoi(t.rows[k][0]) == static_cast<int>(k));
      CHECK(t.rows[k][8] == "true");
      // The average lies between the smallest and the largest angle.
      const double average = std::stod(t.rows[k][1]), lo = std::stod(t.rows[k][9]),
                   hi = std::stod(t.rows[k][10]);
      CHECK(lo > 0.0);
      CHECK(lo <= average);
      CHECK(hi >= average);
      CHECK(hi < M_PI);
      // Newton factorizes at least once per iteration; dynamics counts
      // those of its integrator.
      const long iterations = std::stol(t.rows[k][7]), factorizations = std::stol(t.rows[k][11]);
      CHECK(factorizations >= 0);
      if (std::string(solver) == "newton") CHECK(factorizations >= iterations);
    }
    const double last_angle = std::stod(t.rows.back()[1]),
                 last_torque = std::stod(t.rows.back()[6]);
    CHECK(last_angle == doctest::Approx(1.9).epsilon(1e-12));
    CHECK(last_torque > 0.0);
    // Energies increase as the dome opens.
    for (size_t k = 1; k < t.rows.size(); ++k)
      CHECK(std::stod(t.rows[k][2]) > std::stod(t.rows[k - 1][2]));

    const nlohmann::json s = read_json(dir / "out" / "summary.json");
    CHECK(s["status"] == "converged");
    CHECK(s["solver"] == solver);
    const nlohmann::json& d = s["deployment"];
    CHECK(d["actuation"] == "average_opening_angle");
    CHECK(d["status"] == "completed");
    CHECK(d["steps"] == 4);
    CHECK(d["final_average_angle"].get<double>() == doctest::Approx(1.9).epsilon(1e-12));
    CHECK(d["final_torque"].get<double>() == doctest::Approx(last_torque).epsilon(1e-12));
    CHECK(d["target_average_angle"].get<double>() == 1.9);
    CHECK(d["table"] == "deployment.csv");
    // Without failed attempts (and without loads, so without a twin) the
    // run's factorizations are its steps'.
    long table_factorizations = 0;
    for (const auto& row : t.rows) table_factorizations += std::stol(row[11]);
    CHECK(d["failed_attempts"] == 0);
    CHECK(d["factorizations"].get<long>() == table_factorizations);
    CHECK(d["curvature_dropped"] == 0);
    CHECK(d["round_off_floor_steps"] == 0);  // the sample converges below the tolerance
    // Newton's chord corrections: their own test case below.
    if (std::string(solver) == "dynamics") CHECK(d["chord_corrections"] == 0);
    // One VTK snapshot per step: 5 times, 3 parts each (rods, frames, joints).
    const std::string pvd = read_text(dir / "out" / "series.pvd");
    CHECK(count(pvd, "timestep=") == 15);
    // Each step's time is its average opening angle (the rods' entries).
    for (size_t k = 0; k < t.rows.size(); ++k) {
      const std::string rods = "part=\"0\" name=\"rods\" file=\"rods_00000" + std::to_string(k);
      const size_t at = pvd.find(rods);
      REQUIRE(at != std::string::npos);
      const size_t open = pvd.rfind("timestep=\"", at) + 10;
      CHECK(std::stod(pvd.substr(open)) == doctest::Approx(std::stod(t.rows[k][1])));
    }
    CHECK(fs::exists(dir / "out" / "rods_000004.vtp"));
    if (matplotlib_available()) {
      CHECK(fs::exists(dir / "out" / "deployment.png"));
      CHECK(d["plot"] == "deployment.png");
    } else {
      CHECK(d["plot"].is_null());
      CHECK(r.errors.find("deployment.png skipped") != std::string::npos);
    }
    ++solvers;
  }
  CHECK(solvers == 2);
}

TEST_CASE("the deployment plot runs without a shell: quotes and $(...) in the output folder") {
  if (!matplotlib_available()) XSHELL_SKIP("no python3 with matplotlib: no deployment plot");
  const ScratchDirectory scratch("deploy-plot-name");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj());
  write_text(dir / "run.json",
             deploy_config(R"({"average_opening_angle": 1.7, "steps": 1})", "newton"));
  // The folder's name is quoted for the shell that runs this test, and
  // reaches xshell (and the plot) as it is.
  const std::string name = "it's a $(touch pwned) `touch pwned2` dir";
  const CommandResult r =
      run_xshell("relax run.json --out \"it's a \\$(touch pwned) \\`touch pwned2\\` dir\"", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  CHECK(fs::exists(dir / name / "deployment.png"));
  CHECK(read_json(dir / name / "summary.json")["deployment"]["plot"] == "deployment.png");
  CHECK_FALSE(fs::exists(dir / "pwned"));
  CHECK_FALSE(fs::exists(dir / name / "pwned"));
  CHECK_FALSE(fs::exists(dir / "pwned2"));
}

TEST_CASE("the deployment plot labels energy and torque with the configured units") {
  CHECK(plot_labels({}).energy == "energy");
  CHECK(plot_labels({}).torque == "torque dE/dA (energy per radian)");
  CHECK(plot_labels({"mm", "N"}).energy == "energy [N mm]");
  CHECK(plot_labels({"mm", "N"}).torque == "torque dE/dA [N mm/rad]");
  if (!matplotlib_available()) XSHELL_SKIP("no python3 with matplotlib: no deployment plot");
  const ScratchDirectory scratch("deploy-plot-units");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj());
  const std::string plain = deploy_config(R"({"average_opening_angle": 1.7, "steps": 1})");
  std::string with_units = plain;
  with_units.replace(with_units.find("\"linkage\""), 0,
                     R"("units": {"length": "m", "force": "N"}, )");
  write_text(dir / "plain.json", plain);
  write_text(dir / "units.json", with_units);
  for (const char* name : {"plain", "units"}) {
    const CommandResult r = run_xshell(std::string("relax ") + name + ".json --out " + name, dir);
    CAPTURE(r.errors);
    REQUIRE(r.status == 0);
    REQUIRE(fs::exists(dir / name / "deployment.png"));
  }
  CHECK(read_json(dir / "units" / "summary.json")["configuration"]["units"]["force"] == "N");
  // The same table, other labels: another picture.
  CHECK(read_text(dir / "units" / "deployment.csv") == read_text(dir / "plain" / "deployment.csv"));
  CHECK(read_text(dir / "units" / "deployment.png") != read_text(dir / "plain" / "deployment.png"));
}

TEST_CASE("relax --init continues a deployment, and closing it back returns the start energy") {
  const ScratchDirectory scratch("deploy-init");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj());
  write_text(dir / "open.json", deploy_config(R"({"average_opening_angle": 1.8, "steps": 3})"));
  REQUIRE(run_xshell("relax open.json --out opened", dir).status == 0);
  const Table opened = read_table(dir / "opened" / "deployment.csv");
  const double start_angle = std::stod(opened.rows.front()[1]),
               start_energy = std::stod(opened.rows.front()[2]);
  const double open_energy = std::stod(opened.rows.back()[2]);
  // Further open from the saved state.
  write_text(dir / "further.json", deploy_config(R"({"average_opening_angle": 2.0, "steps": 2})"));
  const CommandResult further =
      run_xshell("relax further.json --init opened/state.json --out further", dir);
  CAPTURE(further.errors);
  REQUIRE(further.status == 0);
  const Table f = read_table(dir / "further" / "deployment.csv");
  CHECK(std::stod(f.rows.front()[1]) ==
        doctest::Approx(1.8).epsilon(1e-12));  // it starts where it stopped
  CHECK(std::stoi(f.rows.front()[7]) == 0);    // already in equilibrium
  CHECK(std::stod(f.rows.back()[1]) == doctest::Approx(2.0).epsilon(1e-12));
  // Back to the start angle.
  write_text(dir / "close.json", deploy_config(R"({"average_opening_angle": )" +
                                               std::to_string(start_angle) + R"(, "steps": 4})"));
  const CommandResult close =
      run_xshell("relax close.json --init further/state.json --out closed", dir);
  CAPTURE(close.errors);
  REQUIRE(close.status == 0);
  const Table c = read_table(dir / "closed" / "deployment.csv");
  CHECK(std::stod(c.rows.back()[1]) == doctest::Approx(start_angle).epsilon(1e-6));
  CHECK(std::abs(std::stod(c.rows.back()[2]) - start_energy) <= 1e-8 * open_energy);
}

TEST_CASE("relax with prescribed joint angles, and the errors of a deployment") {
  const ScratchDirectory scratch("deploy-joints");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj(true));
  write_text(dir / "run.json",
             deploy_config(R"({"joint_angles": [{"vertex": 4, "angle": 1.9}], "steps": 3})"));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["deployment"]["actuation"] == "joint_angles");
  CHECK(s["deployment"]["target_average_angle"].is_null());
  CHECK(s["opening_angles"][4].get<double>() == doctest::Approx(1.9).epsilon(1e-12));
  CHECK(read_table(dir / "out" / "deployment.csv").rows.size() == 4);

  // Vertex 9 is a free rod end: no opening angle to drive.
  write_text(dir / "end.json", deploy_config(R"({"joint_angles": [{"vertex": 9, "angle": 1.9}]})"));
  const CommandResult end = run_xshell("relax end.json", dir);
  CHECK(end.status == 2);
  CHECK(end.errors.find("deployment.joint_angles[0].vertex") != std::string::npos);
  // Every opening angle held by a support: the average cannot move.
  std::string all_fixed = deploy_config(R"({"average_opening_angle": 1.9})");
  std::string supports =
      R"("supports": [{"vertex": 4, "fix": ["position", "orientation", "opening_angle"]})";
  for (int v : {0, 1, 2, 3, 5, 6, 7, 8})
    supports += R"(, {"vertex": )" + std::to_string(v) + R"(, "fix": ["opening_angle"]})";
  supports += "]";
  all_fixed.replace(
      all_fixed.find(R"("supports")"),
      all_fixed.find("\n", all_fixed.find(R"("supports")")) - all_fixed.find(R"("supports")") - 1,
      supports);
  write_text(dir / "fixed.json", all_fixed);
  const CommandResult fixed = run_xshell("relax fixed.json", dir);
  CAPTURE(fixed.errors);
  CHECK(fixed.status == 2);
  CHECK(fixed.errors.find("deployment.average_opening_angle") != std::string::npos);
}

TEST_CASE("relax: a deployment with kinetic damping is refused, not ignored") {
  const ScratchDirectory scratch("deploy-kinetic");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj(true));
  write_text(dir / "run.json", deploy_config(R"({"average_opening_angle": 1.9, "steps": 2})"));
  const CommandResult r = run_xshell("relax run.json --solver kinetic-damping", dir);
  CHECK(r.status == 2);
  CHECK(r.errors.find("deployment: not available with solver.method \"kinetic-damping\"") !=
        std::string::npos);
  CHECK(!fs::exists(dir / "out" / "summary.json"));
}

TEST_CASE("relax: a deployment with edge-vector joints is refused, not run on the wrong unknowns") {
  const ScratchDirectory scratch("deploy-edge-vectors");
  const fs::path& dir = scratch.path();
  write_text(dir / "dome.obj", dome_obj(true));
  std::string config = deploy_config(R"({"average_opening_angle": 1.9, "steps": 2})");
  config.insert(config.find('{') + 1, R"("joints": "edge_vectors",)");
  write_text(dir / "run.json", config);
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  CHECK(r.status == 2);
  CHECK(r.errors.find("deployment: needs \"joints\": \"rotation\"") != std::string::npos);
}

}  // namespace xshell::test
