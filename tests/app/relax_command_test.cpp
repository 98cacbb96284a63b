#include <doctest/doctest.h>
#include <signal.h>
#include <spawn.h>
#include <unistd.h>

#include <map>
#include <thread>

#include "command_runner.hpp"

extern char** environ;

namespace xshell::test {

TEST_CASE("relax: the sample runs and writes summary.json, state.json and the VTK series") {
  const ScratchDirectory scratch("sample");
  const fs::path& dir = scratch.path();
  write_text(dir / "run.json", sample_config(dir / "out"));
  const CommandResult r = run_xshell("relax run.json", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["converged"] == true);
  CHECK(s["stable"] == true);
  CHECK(s["status"] == "converged");
  CHECK(s["solver"] == "newton");
  CHECK(s["iterations"].get<int>() > 0);
  CHECK(s["wall_seconds"].get<double>() > 0.0);
  CHECK(s["unknowns"].get<int>() > s["free_unknowns"].get<int>());
  CHECK(s["gradient_norm"].get<double>() <= s["gradient_tolerance"].get<double>());
  for (const char* key : {"total", "stretching", "bending", "twisting", "external"})
    CHECK(s["energy"].contains(key));
  CHECK(s["energy"]["total"].get<double>() ==
        doctest::Approx(
            s["energy"]["stretching"].get<double>() + s["energy"]["bending"].get<double>() +
            s["energy"]["twisting"].get<double>() + s["energy"]["external"].get<double>()));
  CHECK(s["vertices"].size() == 32);
  CHECK(s["opening_angles"].size() == 32);
  CHECK(s["opening_angles"][0].is_null());          // a free end
  CHECK(s["opening_angles"][1].get<double>() > 0);  // a joint
  CHECK(s["default_support"].is_null());
  CHECK(s["configuration"]["subdivisions"] == 6);
  CHECK(s["version"].is_string());
  CHECK(read_json(dir / "out" / "state.json")["format"] == "xshell-state");
  CHECK(fs::exists(dir / "out" / "series.pvd"));
  CHECK(fs::exists(dir / "out" / "rods_000000.vtp"));
  // Every converged run writes the fabrication data (README, "Fabrication data").
  const nlohmann::json fab = read_json(dir / "out" / "fabrication.json");
  CHECK(fab["rods"].size() > 0);
  CHECK(fab["joints"].size() > 0);
  CHECK(fs::exists(dir / "out" / "fabrication.csv"));
  CHECK(fs::exists(dir / "out" / "fabrication.svg"));
  // The supported corners did not move; the loaded middle sagged.
  CHECK(s["vertices"][1][2].get<double>() == doctest::Approx(0.0).epsilon(1e-12));
  CHECK(s["vertices"][13][2].get<double>() < -1e-3);
}

// The compressor attribute of every .vtp file in `dir` ("" for none), one
// entry per distinct value, with how many files carry it.
std::map<std::string, int> compressors(const fs::path& dir) {
  std::map<std::string, int> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".vtp") continue;
    const std::string text = read_text(entry.path());
    const std::string key = "compressor=\"";
    const size_t start = text.find(key);
    const size_t begin = start == std::string::npos ? start : start + key.size();
    ++found[start == std::string::npos ? "" : text.substr(begin, text.find('"', begin) - begin)];
  }
  return found;
}

TEST_CASE("relax: output.compression chooses the compressor of every VTK file, LZ4 by default") {
  const ScratchDirectory scratch("compression");
  const fs::path& dir = scratch.path();
  const std::string config = sample_config(dir / "lz4");
  std::string zlib = sample_config(dir / "zlib");
  const std::string end = "zlib\"}";
  zlib.replace(zlib.find(end), end.size(), "zlib\", \"compression\": \"zlib\"}");
  write_text(dir / "lz4.json", config);
  write_text(dir / "zlib.json", zlib);
  REQUIRE(run_xshell("relax lz4.json", dir).status == 0);
  REQUIRE(run_xshell("relax zlib.json", dir).status == 0);
  const auto lz4_files = compressors(dir / "lz4");
  const auto zlib_files = compressors(dir / "zlib");
  REQUIRE(lz4_files.size() == 1);
  REQUIRE(zlib_files.size() == 1);
  CHECK(lz4_files.begin()->first == "vtkLZ4DataCompressor");
  CHECK(zlib_files.begin()->first == "vtkZLibDataCompressor");
  CHECK(lz4_files.begin()->second > 8);  // the series and the engineering files
  CHECK(zlib_files.begin()->second == lz4_files.begin()->second);
  CHECK(read_json(dir / "zlib" / "summary.json")["configuration"]["output"]["compression"] ==
        "zlib");
}

TEST_CASE("relax --init from a written state reproduces it without iterating") {
  const ScratchDirectory scratch("init");
  const fs::path& dir = scratch.path();
  write_text(dir / "run.json", sample_config(dir / "first"));
  REQUIRE(run_xshell("relax run.json", dir).status == 0);
  const CommandResult r = run_xshell("relax run.json --init first/state.json --out second", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json a = read_json(dir / "first" / "summary.json"),
                       b = read_json(dir / "second" / "summary.json");
  CHECK(b["iterations"] == 0);
  CHECK(b["energy"]["total"].get<double>() ==
        doctest::Approx(a["energy"]["total"].get<double>()).epsilon(1e-12));
  int compared = 0;
  for (size_t v = 0; v < a["vertices"].size(); ++v)
    for (int c = 0; c < 3; ++c) {
      CHECK(std::abs(a["vertices"][v][c].get<double>() - b["vertices"][v][c].get<double>()) <
            1e-12);
      ++compared;
    }
  CHECK(compared == 96);
}

TEST_CASE("relax --init accepts a state of the same linkage under other loads and materials") {
  // A state is only where the solve starts: a sweep over loads or materials
  // continues from the previous equilibrium and reaches the same answer as
  // a start from the flat input.
  const ScratchDirectory scratch("init-sweep");
  const fs::path& dir = scratch.path();
  write_text(dir / "light.json", sample_config(dir / "light"));
  std::string heavy = sample_config(dir / "heavy");
  heavy.replace(heavy.find("\"young_modulus\": 2.0e10"), 23, "\"young_modulus\": 1.0e10");
  heavy.replace(heavy.find("\"force\": [0, 0, -5.0]"), 21, "\"force\": [0, 0, -9.0]");
  write_text(dir / "heavy.json", heavy);
  REQUIRE(run_xshell("relax light.json", dir).status == 0);
  REQUIRE(run_xshell("relax heavy.json", dir).status == 0);
  const CommandResult r = run_xshell("relax heavy.json --init light/state.json --out warm", dir);
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  const nlohmann::json cold = read_json(dir / "heavy" / "summary.json"),
                       warm = read_json(dir / "warm" / "summary.json");
  const nlohmann::json light = read_json(dir / "light" / "summary.json");
  CHECK(warm["converged"] == true);
  CHECK(warm["configuration"]["material"]["young_modulus"].get<double>() == 1.0e10);
  // The heavier, softer linkage sags further than the light one, and the warm
  // start finds the same equilibrium as the cold one.
  CHECK(warm["vertices"][13][2].get<double>() < 1.5 * light["vertices"][13][2].get<double>());
  CHECK(warm["energy"]["total"].get<double>() ==
        doctest::Approx(cold["energy"]["total"].get<double>()).epsilon(1e-9));
  int compared = 0;
  for (size_t v = 0; v < cold["vertices"].size(); ++v)
    for (int c = 0; c < 3; ++c) {
      CHECK(std::abs(cold["vertices"][v][c].get<double>() - warm["vertices"][v][c].get<double>()) <
            1e-8);
      ++compared;
    }
  CHECK(compared == 96);
}

TEST_CASE("relax: invalid input exits 2 with one clear message") {
  const ScratchDirectory scratch("invalid");
  const fs::path& dir = scratch.path();
  struct Case {
    const char* name;
    std::string config;
    const char* message;
  };
  const fs::path out = dir / "out";
  std::string unknown = sample_config(out);
  unknown.replace(unknown.find("\"subdivisions\""), 14, "\"subdivision\"");
  std::string bad_vertex = sample_config(out);
  bad_vertex.replace(bad_vertex.find("\"vertex\": 13"), 12, "\"vertex\": 99");
  std::string missing_file = sample_config(out, "", "no_such_file.obj");
  std::string truncated = sample_config(out).substr(0, 120);
  const Case cases[] = {
      {"unknown key", unknown, "did you mean \"subdivisions\""},
      {"vertex out of range", bad_vertex, "loads.forces[0].vertex"},
      {"missing linkage file", missing_file, "no_such_file.obj"},
      {"malformed JSON", truncated, "invalid JSON"},
  };
  int checked = 0;
  for (const Case& c : cases) {
    const std::string name = c.name;
    CAPTURE(name);
    write_text(dir / "bad.json", c.config);
    const CommandResult r = run_xshell("relax bad.json", dir);
    CAPTURE(r.errors);
    CHECK(r.status == 2);
    CHECK(r.errors.find(c.message) != std::string::npos);
    CHECK(r.errors.find("xshell: error:") != std::string::npos);
    ++checked;
  }
  CHECK(run_xshell("relax", dir).status == 2);                      // usage
  CHECK(run_xshell("relax no_such_config.json", dir).status == 2);  // unreadable configuration
  CHECK(checked == 4);
}

TEST_CASE("relax --init refuses a state that belongs to another linkage") {
  const ScratchDirectory scratch("foreign");
  const fs::path& dir = scratch.path();
  write_text(dir / "saddle.json", sample_config(dir / "saddle", "", "saddle.obj"));
  write_text(dir / "grid.json", sample_config(dir / "grid"));
  REQUIRE(run_xshell("relax saddle.json", dir).status == 0);
  const CommandResult r = run_xshell("relax grid.json --init saddle/state.json", dir);
  CHECK(r.status == 2);
  CHECK(r.errors.find("belongs to another linkage") != std::string::npos);
}

TEST_CASE("relax: an output directory that cannot be written exits 4") {
  const ScratchDirectory scratch("unwritable");
  const fs::path& dir = scratch.path();
  write_text(dir / "a_file", "not a directory");
  write_text(dir / "run.json", sample_config(dir / "a_file" / "out"));
  const CommandResult r = run_xshell("relax run.json", dir);
  CHECK(r.status == 4);
  CHECK(r.errors.find("a_file") != std::string::npos);
}

TEST_CASE("relax: SIGINT writes the last state and an interrupted summary, and exits 130") {
  const ScratchDirectory scratch("interrupt");
  const fs::path& dir = scratch.path();
  // Slow enough to interrupt: damped dynamics with fictitious masses.
  write_text(
      dir / "run.json",
      sample_config(
          dir / "out",
          R"(, "solver": {"method": "dynamics", "mass": "fictitious", "max_steps": 100000})"));
  const std::string binary = XSHELL_BINARY, config = (dir / "run.json").string();
  char* argv[] = {const_cast<char*>(binary.c_str()), const_cast<char*>("relax"),
                  const_cast<char*>(config.c_str()), const_cast<char*>("--quiet"), nullptr};
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, binary.c_str(), nullptr, nullptr, argv, environ) == 0);
  // Wait until the run has written a few steps, then interrupt it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline &&
         !fs::exists(dir / "out" / "rods_000003.vtp"))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  REQUIRE(fs::exists(dir / "out" / "rods_000003.vtp"));
  kill(pid, SIGINT);
  int raw = 0;
  waitpid(pid, &raw, 0);
  REQUIRE(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 130);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["interrupted"] == true);
  CHECK(s["status"] == "interrupted");
  CHECK(s["converged"] == false);
  CHECK(read_json(dir / "out" / "state.json")["format"] == "xshell-state");
  // The series is closed: it names every step file there is.
  const std::string pvd = read_text(dir / "out" / "series.pvd");
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "out"))
    if (entry.path().extension() == ".vtp") {
      CHECK(pvd.find(entry.path().filename().string()) != std::string::npos);
      ++files;
    }
  CHECK(files >= 4);
}

}  // namespace xshell::test
