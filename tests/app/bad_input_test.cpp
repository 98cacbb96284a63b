// Bad input through the real program: every rejection ends the run with exit
// status 2 and one line "xshell: error: FILE...: what is wrong", before any
// output is written. (The readers' own tests check the messages in more
// detail: tests/io.)
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <algorithm>
#include <functional>

#include "bad_input_support.hpp"
#include "skip.hpp"

namespace xshell::test {

// ---------------------------------------------------------------------------
// The linkage file: every rejection of the OBJ reader, and of the model

TEST_CASE("bad input: OBJ unknown statement") {
  ScratchDirectory dir("obj-statement");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl 1 2\np 1\n"), dir.path(),
                 {"bad.obj:4: ", "unknown statement 'p'"});
}

TEST_CASE("bad input: OBJ faces") {
  ScratchDirectory dir("obj-face");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), dir.path(),
                 {"bad.obj:4: ", "faces ('f')"});
}

TEST_CASE("bad input: OBJ coordinate that is not a number") {
  ScratchDirectory dir("obj-nan-text");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 x 0\nl 1 2\n"), dir.path(),
                 {"bad.obj:2: ", "'x'", "not a number"});
}

TEST_CASE("bad input: OBJ NaN and infinite coordinates") {
  int checked = 0;
  for (const std::string value :
       {"nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e999", "-1e400"}) {
    CAPTURE(value);
    ScratchDirectory dir("obj-nonfinite");
    const CommandResult r = relax_obj(dir, "v 0 0 0\nv 1 0 0\nv 1 " + value + " 0\nl 1 2\nl 2 3\n");
    check_rejected(r, dir.path(), {"bad.obj:3: ", "'" + value + "'"});
    CHECK((contains(r.errors, "not a finite number") || contains(r.errors, "out of the range")));
    ++checked;
  }
  CHECK(checked == 8);
}

TEST_CASE("bad input: OBJ vertex with too few or too many coordinates") {
  ScratchDirectory dir("obj-coordinates");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0\nl 1 2\n"), dir.path(),
                 {"bad.obj:2: ", "needs three"});
  check_rejected(relax_obj(dir, "v 0 0 0 1 2\nv 1 0 0\nl 1 2\n"), dir.path(),
                 {"bad.obj:1: ", "5 coordinates"});
}

TEST_CASE("bad input: OBJ index 0") {
  ScratchDirectory dir("obj-index0");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl 0 1\n"), dir.path(),
                 {"bad.obj:3: ", "index 0", "start at 1"});
}

TEST_CASE("bad input: OBJ index out of range") {
  ScratchDirectory dir("obj-index-range");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl 1 3\n"), dir.path(),
                 {"bad.obj:3: ", "vertex index 3 is out of range", "defines 2 vertices"});
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl -3 1\n"), dir.path(),
                 {"relative vertex index -3"});
}

TEST_CASE("bad input: OBJ index that is not an integer") {
  ScratchDirectory dir("obj-index-text");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl 1 2.0\n"), dir.path(),
                 {"bad.obj:3: ", "'2.0'", "not an integer"});
}

TEST_CASE("bad input: OBJ 'l' with one index") {
  ScratchDirectory dir("obj-short-l");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl 1\n"), dir.path(),
                 {"bad.obj:3: ", "at least two vertex indices"});
}

TEST_CASE("bad input: OBJ self-loop") {
  ScratchDirectory dir("obj-self-loop");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl 1 2\nl 2 2\n"), dir.path(),
                 {"bad.obj:4: ", "self-loop"});
}

TEST_CASE("bad input: OBJ duplicate edge") {
  ScratchDirectory dir("obj-duplicate");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nl 1 2\nl 2 1\n"), dir.path(),
                 {"bad.obj:4: ", "duplicate edge", "line 3"});
}

TEST_CASE("bad input: OBJ zero-length edge") {
  ScratchDirectory dir("obj-zero-length");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nv 1 0 0\nl 1 2\nl 2 3\n"), dir.path(),
                 {"bad.obj:5: ", "zero-length edge"});
}

TEST_CASE("bad input: OBJ coincident vertices") {
  ScratchDirectory dir("obj-coincident");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 0 0\nl 1 2\nl 2 3\nl 3 4\n"),
                 dir.path(), {"bad.obj:4: ", "coincides with vertex 1"});
}

TEST_CASE("bad input: OBJ isolated vertex") {
  ScratchDirectory dir("obj-isolated");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nv 5 5 5\nl 1 2\n"), dir.path(),
                 {"bad.obj:3: ", "isolated"});
}

TEST_CASE("bad input: OBJ vertex of valence above 4") {
  ScratchDirectory dir("obj-valence");
  check_rejected(relax_obj(dir,
                           "v 0 0 0\nv 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                           "l 1 2\nl 1 3\nl 1 4\nl 1 5\nl 1 6\n"),
                 dir.path(), {"bad.obj:1: ", "valence 5", "at most 4"});
}

TEST_CASE("bad input: OBJ disconnected graph") {
  ScratchDirectory dir("obj-disconnected");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nl 1 2\nl 3 4\n"), dir.path(),
                 {"bad.obj:3: ", "not connected"});
}

TEST_CASE("bad input: OBJ without edges (an empty file)") {
  ScratchDirectory dir("obj-empty");
  check_rejected(relax_obj(dir, ""), dir.path(), {"bad.obj: ", "no rod segments"});
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\n"), dir.path(),
                 {"bad.obj: ", "no rod segments"});
}

TEST_CASE("bad input: OBJ of random bytes") {
  ScratchDirectory dir("obj-bytes");
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>((i * 37 + 11) % 256);
  const CommandResult r = relax_obj(dir, bytes);
  check_rejected(r, dir.path(), {"bad.obj:"});
}

TEST_CASE("bad input: a linkage the model refuses (a joint whose two rods are collinear)") {
  ScratchDirectory dir("obj-collinear");
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1 0 0\nv 2 0 0\nl 1 2\nl 2 3\n"), dir.path(),
                 {"bad.obj: ", "vertex 1", "collinear"});
}

TEST_CASE("bad input: a missing linkage file") {
  ScratchDirectory dir("obj-missing");
  check_rejected(relax_config(dir, config_with("no_such.obj")), dir.path(),
                 {"cannot open linkage file 'no_such.obj'", "No such file"});
}

TEST_CASE("bad input: a linkage path that is a folder") {
  ScratchDirectory dir("obj-folder");
  fs::create_directory(dir / "folder.obj");
  check_rejected(relax_config(dir, config_with("folder.obj")), dir.path(),
                 {"cannot open linkage file 'folder.obj'", "folder"});
}

TEST_CASE("bad input: an unreadable linkage file (mode 000)") {
  ScratchDirectory dir("obj-unreadable");
  fs::copy_file(grid_obj(), dir / "locked.obj");
  fs::permissions(dir / "locked.obj", fs::perms::none);
  write_text(dir / "run.json", config_with("locked.obj"));
  const CommandResult r = run_xshell_unprivileged("relax run.json", dir.path());
  if (r.status == -2) XSHELL_SKIP(r.errors + ": the unreadable-file case cannot be checked here");
  check_rejected(r, dir.path(), {"cannot open linkage file 'locked.obj'", "Permission denied"});
}

// ---------------------------------------------------------------------------
// The configuration

TEST_CASE("bad input: a missing configuration file") {
  ScratchDirectory dir("config-missing");
  check_rejected(run_xshell("relax no_such.json", dir.path()), dir.path(),
                 {"cannot open configuration file 'no_such.json'", "No such file"});
}

TEST_CASE("bad input: a configuration path that is a folder") {
  ScratchDirectory dir("config-folder");
  fs::create_directory(dir / "run.json");
  check_rejected(run_xshell("relax run.json", dir.path()), dir.path(),
                 {"configuration file 'run.json'", "folder"});
}

TEST_CASE("bad input: an unreadable configuration file (mode 000)") {
  ScratchDirectory dir("config-unreadable");
  write_text(dir / "run.json", grid_config());
  fs::permissions(dir / "run.json", fs::perms::none);
  const CommandResult r = run_xshell_unprivileged("relax run.json", dir.path());
  if (r.status == -2) XSHELL_SKIP(r.errors + ": the unreadable-file case cannot be checked here");
  check_rejected(r, dir.path(), {"cannot open configuration file 'run.json'", "Permission denied"});
}

TEST_CASE("bad input: JSON that does not parse gives the line and the column") {
  ScratchDirectory dir("config-syntax");
  // Line 3 ends with a second comma at column 21.
  check_rejected(relax_config(dir, "{\n  \"linkage\": \"a.obj\",\n  \"subdivisions\": 8,,\n}"),
                 dir.path(), {"run.json:3:21: invalid JSON"});
  // Truncated: the end of the text.
  check_rejected(relax_config(dir, "{\"linkage\": \"a.obj\""), dir.path(),
                 {"run.json:1:20: invalid JSON"});
  check_rejected(relax_config(dir, ""), dir.path(), {"run.json:1:1: invalid JSON"});
}

TEST_CASE("bad input: NaN and Infinity literals are not JSON") {
  int checked = 0;
  for (const std::string literal : {"NaN", "nan", "Infinity", "-Infinity", "inf"}) {
    CAPTURE(literal);
    ScratchDirectory dir("config-nan");
    const CommandResult r =
        relax_config(dir, grid_config(R"(, "loads": {"gravity": [0, 0, )" + literal + "]}"));
    check_rejected(r, dir.path(), {"run.json:", "invalid JSON", "JSON has no NaN or Infinity"});
    ++checked;
  }
  CHECK(checked == 5);
}

TEST_CASE("bad input: numbers that overflow to infinity, anywhere") {
  struct Case {
    std::string from, to, path;
  };
  const std::vector<Case> cases = {
      {"\"young_modulus\": 2.0e10", "\"young_modulus\": 1e999", "material.young_modulus"},
      {"\"density\": 1800", "\"density\": 1e400", "material.density"},
      {"\"width\": 0.01", "\"width\": 1e999", "material.cross_section.width"},
      {"\"height\": 0.007", "\"height\": -1e999", "material.cross_section.height"},
      {"\"subdivisions\": 4", "\"subdivisions\": 1e999", "subdivisions"},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.path);
    ScratchDirectory dir("config-overflow");
    check_rejected(relax_config(dir, grid_config_replacing(c.from, c.to)), dir.path(),
                   {"run.json: " + c.path + ": number", "overflows to infinity"});
    ++checked;
  }
  const std::vector<std::pair<std::string, std::string>> more = {
      {R"(, "loads": {"gravity": [0, 0, -1e999]})", "loads.gravity[2]"},
      {R"(, "loads": {"forces": [{"vertex": 13, "force": [1e999, 0, 0]}]})",
       "loads.forces[0].force[0]"},
      {R"(, "supports": [{"vertex": 1e999, "fix": ["position"]}])", "supports[0].vertex"},
      {R"(, "solver": {"gradient_tolerance": 1e999})", "solver.gradient_tolerance"},
      {R"(, "solver": {"method": "dynamics", "damping": 1e999})", "solver.damping"},
      {R"(, "deployment": {"average_opening_angle": 1e999})", "deployment.average_opening_angle"},
  };
  for (const auto& [extra, path] : more) {
    CAPTURE(path);
    ScratchDirectory dir("config-overflow");
    check_rejected(relax_config(dir, grid_config(extra)), dir.path(),
                   {"run.json: " + path + ": number", "overflows"});
    ++checked;
  }
  CHECK(checked == 11);
}

TEST_CASE("bad input: an unknown key, with the closest valid key suggested") {
  ScratchDirectory dir("config-unknown");
  check_rejected(
      relax_config(dir, grid_config_replacing("\"subdivisions\"", "\"subdivision\"")), dir.path(),
      {"unknown key \"subdivision\" at the top level", "did you mean \"subdivisions\"?"});
  check_rejected(
      relax_config(dir, grid_config_replacing("\"young_modulus\"", "\"youngs_modulus\"")),
      dir.path(),
      {"unknown key \"youngs_modulus\" in material", "did you mean \"young_modulus\"?"});
  check_rejected(relax_config(dir, grid_config(R"(, "solver": {"max_iteration": 5})")), dir.path(),
                 {"in solver", "did you mean \"max_iterations\"?"});
  // Nothing close: the valid keys are listed.
  check_rejected(relax_config(dir, grid_config(R"(, "colour": "red")")), dir.path(),
                 {"unknown key \"colour\"", "valid keys are \"linkage\""});
}

TEST_CASE("bad input: a key given twice") {
  ScratchDirectory dir("config-twice");
  check_rejected(relax_config(dir, grid_config(R"(, "subdivisions": 5)")), dir.path(),
                 {"run.json: subdivisions: key given twice"});
}

TEST_CASE("bad input: wrong types") {
  ScratchDirectory dir("config-types");
  check_rejected(
      relax_config(dir, grid_config_replacing("2.0e10", "\"2.0e10\"")), dir.path(),
      {"run.json: material.young_modulus: expected a number, got a string (\"2.0e10\")"});
  check_rejected(
      relax_config(dir, grid_config_replacing("\"subdivisions\": 4", "\"subdivisions\": 4.5")),
      dir.path(), {"run.json: subdivisions: expected an integer"});
  check_rejected(
      relax_config(dir, grid_config_replacing("\"subdivisions\": 4", "\"subdivisions\": \"4\"")),
      dir.path(), {"run.json: subdivisions: expected an integer"});
  check_rejected(relax_config(dir, grid_config(R"(, "supports": {"vertex": 1})")), dir.path(),
                 {"run.json: supports: expected an array, got an object"});
  check_rejected(relax_config(dir, grid_config(R"(, "loads": {"gravity": [0, -9.81]})")),
                 dir.path(), {"run.json: loads.gravity: expected an array of three numbers"});
  check_rejected(relax_config(dir, grid_config(R"(, "solver": {"first_order": "yes"})")),
                 dir.path(), {"run.json: solver.first_order: expected true or false"});
  check_rejected(relax_config(dir, grid_config(R"(, "solver": {"method": "newtonn"})")), dir.path(),
                 {"run.json: solver.method: \"newtonn\" is not a valid choice", "\"newton\""});
  check_rejected(relax_config(dir, "[1, 2, 3]"), dir.path(), {"must be a JSON object"});
}

TEST_CASE("bad input: a missing required key") {
  ScratchDirectory dir("config-missing-key");
  check_rejected(relax_config(dir, grid_config_replacing("\"young_modulus\": 2.0e10, ", "")),
                 dir.path(), {"run.json: missing required key \"material.young_modulus\""});
  check_rejected(relax_config(dir, "{}"), dir.path(),
                 {"run.json: missing required key \"linkage\""});
}

TEST_CASE("bad input: a negative or zero Young's modulus") {
  ScratchDirectory dir("config-modulus");
  check_rejected(relax_config(dir, grid_config_replacing("2.0e10", "-2.0e10")), dir.path(),
                 {"run.json: material.young_modulus: must be > 0"});
  check_rejected(relax_config(dir, grid_config_replacing("2.0e10", "0")), dir.path(),
                 {"run.json: material.young_modulus: must be > 0, got 0"});
}

TEST_CASE("bad input: negative or zero cross-section dimensions") {
  ScratchDirectory dir("config-section");
  check_rejected(relax_config(dir, grid_config_replacing("\"width\": 0.01", "\"width\": -0.01")),
                 dir.path(), {"run.json: material.cross_section.width: must be > 0"});
  check_rejected(relax_config(dir, grid_config_replacing("\"height\": 0.007", "\"height\": 0")),
                 dir.path(), {"run.json: material.cross_section.height: must be > 0"});
}

TEST_CASE("bad input: a negative density") {
  ScratchDirectory dir("config-density");
  check_rejected(relax_config(dir, grid_config_replacing("\"density\": 1800", "\"density\": -1")),
                 dir.path(), {"run.json: material.density: must be >= 0"});
}

TEST_CASE("bad input: a Poisson ratio outside (-1, 0.5), inside it runs") {
  int checked = 0;
  for (const std::string nu : {"0.5", "-1", "0.7", "-1.5", "2"}) {
    CAPTURE(nu);
    ScratchDirectory dir("config-poisson");
    check_rejected(
        relax_config(dir, grid_config_replacing("\"density\": 1800",
                                                "\"density\": 1800, \"poisson_ratio\": " + nu)),
        dir.path(), {"run.json: material.poisson_ratio: must be in (-1, 0.5), got " + nu});
    ++checked;
  }
  CHECK(checked == 5);
  for (const std::string nu : {"0.49", "-0.99"}) {
    CAPTURE(nu);
    ScratchDirectory dir("config-poisson-ok");
    const CommandResult r = relax_config(
        dir,
        grid_config_replacing("\"density\": 1800", "\"density\": 1800, \"poisson_ratio\": " + nu));
    CAPTURE(r.errors);
    CHECK(r.status == 0);
  }
}

TEST_CASE("bad input: subdivisions below the model's minimum (3), 3 runs") {
  int checked = 0;
  for (const std::string n : {"2", "1", "0", "-3"}) {
    CAPTURE(n);
    ScratchDirectory dir("config-subdivisions");
    check_rejected(
        relax_config(dir, grid_config_replacing("\"subdivisions\": 4", "\"subdivisions\": " + n)),
        dir.path(), {"run.json: subdivisions: must be >= 3, got " + n});
    ++checked;
  }
  CHECK(checked == 4);
  ScratchDirectory dir("config-subdivisions-ok");
  const CommandResult r =
      relax_config(dir, grid_config_replacing("\"subdivisions\": 4", "\"subdivisions\": 3"));
  CAPTURE(r.errors);
  CHECK(r.status == 0);
}

TEST_CASE("bad input: subdivisions too many for any machine") {
  ScratchDirectory dir("config-subdivisions-huge");
  check_rejected(relax_config(dir, grid_config_replacing("\"subdivisions\": 4",
                                                         "\"subdivisions\": 2000000000")),
                 dir.path(), {"run.json: subdivisions: 2000000000 x 40 segments", "at most"});
}

TEST_CASE("bad input: a support naming a vertex that does not exist") {
  ScratchDirectory dir("config-support-vertex");
  check_rejected(
      relax_config(dir, grid_config(R"(, "supports": [{"vertex": 32, "fix": ["position"]}])")),
      dir.path(),
      {"run.json: supports[0].vertex: vertex 32 is out of range; the linkage has 32 vertices"});
  check_rejected(
      relax_config(dir, grid_config(R"(, "supports": [{"vertex": -1, "fix": ["position"]}])")),
      dir.path(), {"run.json: supports[0].vertex: a vertex index is 0-based"});
}

TEST_CASE("bad input: a force naming a vertex that does not exist") {
  ScratchDirectory dir("config-force-vertex");
  check_rejected(
      relax_config(
          dir,
          grid_config(
              R"(, "loads": {"forces": [{"vertex": 13, "force": [0, 0, -1]}, {"vertex": 99, "force": [0, 0, -1]}]})")),
      dir.path(), {"run.json: loads.forces[1].vertex: vertex 99 is out of range"});
}

TEST_CASE("bad input: a deployment naming a vertex that does not exist") {
  ScratchDirectory dir("config-deployment-vertex");
  check_rejected(
      relax_config(
          dir, grid_config(R"(, "deployment": {"joint_angles": [{"vertex": 40, "angle": 1.0}]})")),
      dir.path(), {"run.json: deployment.joint_angles[0].vertex: vertex 40 is out of range"});
}

TEST_CASE("bad input: a deployment that drives a free rod end") {
  ScratchDirectory dir("config-deployment-free-end");
  check_rejected(
      relax_config(
          dir, grid_config(R"(, "deployment": {"joint_angles": [{"vertex": 0, "angle": 1.0}]})")),
      dir.path(), {"run.json: deployment.joint_angles[0].vertex: vertex 0 is a free rod end"});
}

TEST_CASE("bad input: a deployment with edge-vector joints") {
  ScratchDirectory dir("config-deployment-edge-vectors");
  check_rejected(relax_config(dir, grid_config(R"(, "joints": "edge_vectors",
  "deployment": {"average_opening_angle": 1.2})")),
                 dir.path(), {"run.json: deployment: needs \"joints\": \"rotation\""});
}

TEST_CASE("bad input: a support that does not apply to its vertex names its key") {
  ScratchDirectory dir("config-support-kind");
  // Vertex 0 of the grid is a free rod end: it has no opening angle. The
  // mistake is in the configuration, not in the OBJ.
  check_rejected(
      relax_config(dir, grid_config(R"(, "supports": [{"vertex": 0, "fix": ["opening_angle"]}])")),
      dir.path(),
      {"run.json: supports[0].fix[0]: \"opening_angle\": vertex 0 is a free rod end",
       "has no opening angle"});
  // Every support fixing everything: the free ends' opening angles.
  std::string all;
  for (int v = 0; v < 32; ++v)
    all += std::string(v ? ", " : "") + "{\"vertex\": " + std::to_string(v) +
           ", \"fix\": [\"position\", \"orientation\", \"opening_angle\"]}";
  const CommandResult everything = relax_config(dir, grid_config(", \"supports\": [" + all + "]"));
  check_rejected(everything, dir.path(), {"run.json: supports[0].fix[2]", "free rod end"});
  CHECK_FALSE(contains(everything.errors, "grid.obj"));
  // An opening angle at an edge-vector joint (vertex 12 of the grid).
  const CommandResult edge_vectors = relax_config(dir, grid_config(R"(, "joints": "edge_vectors",
  "supports": [{"vertex": 12, "fix": ["position", "opening_angle"]}])"));
  check_rejected(edge_vectors, dir.path(),
                 {"run.json: supports[0].fix[1]: \"opening_angle\": edge-vector joints"});
  CHECK_FALSE(contains(edge_vectors.errors, "grid.obj"));
}

TEST_CASE("bad input: one vertex in two supports with conflicting displacements names both") {
  ScratchDirectory dir("config-support-twice");
  check_rejected(relax_config(dir, grid_config(R"(, "supports": [
    {"vertex": 1, "fix": ["position"], "displacement": [0, 0, 0.01]},
    {"vertex": 4, "fix": ["position"]},
    {"vertex": 1, "fix": ["z"], "displacement": [0, 0, -0.01]}])")),
                 dir.path(),
                 {"run.json: supports[2]: vertex 1 is also held by supports[0]", "z component"});
}

TEST_CASE("bad input: command-line usage in one line naming what is wrong") {
  ScratchDirectory dir("usage");
  write_text(dir / "run.json", grid_config());
  check_rejected(
      run_xshell("solve run.json", dir.path()), dir.path(),
      {"unknown command 'solve'", "relax, render, fabricate and design", "xshell --help"});
  check_rejected(run_xshell("", dir.path()), dir.path(), {"no command given"});
  check_rejected(run_xshell("--fast relax run.json", dir.path()), dir.path(),
                 {"unknown option '--fast'"});
  check_rejected(run_xshell("relax", dir.path()), dir.path(),
                 {"relax: config is required", "xshell relax --help"});
  check_rejected(run_xshell("relax run.json --no-such-option", dir.path()), dir.path(),
                 {"relax: ", "--no-such-option"});
  check_rejected(run_xshell("render", dir.path()), dir.path(), {"render: "});
  check_rejected(run_xshell("relax run.json --solver fastest", dir.path()), dir.path(),
                 {"--solver: unknown solver \"fastest\""});
  // Help and version still go to stdout with status 0.
  CHECK(run_xshell("--help", dir.path()).status == 0);
  CHECK(run_xshell("relax --help", dir.path()).status == 0);
  CHECK(run_xshell("--version", dir.path()).status == 0);
}

// ---------------------------------------------------------------------------
// --init: a state file

TEST_CASE("bad input: --init with a state of another linkage") {
  ScratchDirectory dir("init-foreign");
  write_text(dir / "grid.json", grid_config());
  REQUIRE(run_xshell("relax grid.json --out first", dir.path()).status == 0);
  // The same graph with other subdivisions is another linkage too.
  write_text(dir / "finer.json",
             grid_config_replacing("\"subdivisions\": 4", "\"subdivisions\": 5"));
  const CommandResult finer = run_xshell("relax finer.json --init first/state.json", dir.path());
  check_rejected(finer, dir.path(),
                 {"first/state.json: the state belongs to another linkage", "\"subdivisions\":5"});
  write_text(dir / "saddle.json",
             config_with((fs::path(XSHELL_SAMPLES_DIR) / "saddle.obj").string()));
  const CommandResult saddle = run_xshell("relax saddle.json --init first/state.json", dir.path());
  check_rejected(saddle, dir.path(), {"the state belongs to another linkage"});
}

TEST_CASE("bad input: --init with a missing, truncated or foreign file") {
  ScratchDirectory dir("init-bad-file");
  write_text(dir / "run.json", grid_config());
  check_rejected(run_xshell("relax run.json --init nothing.json", dir.path()), dir.path(),
                 {"nothing.json: cannot read the state file: No such file"});
  REQUIRE(run_xshell("relax run.json --out first", dir.path()).status == 0);
  const std::string state = read_text(dir / "first" / "state.json");
  write_text(dir / "truncated.json", state.substr(0, state.size() / 2));
  check_rejected(run_xshell("relax run.json --init truncated.json", dir.path()), dir.path(),
                 {"truncated.json:1:", "invalid JSON"});
  check_rejected(run_xshell("relax run.json --init run.json", dir.path()), dir.path(),
                 {"run.json: not an xshell state file"});
  // A state with a segment missing.
  nlohmann::json doc = nlohmann::json::parse(state);
  doc["segments"].erase(doc["segments"].size() - 1);
  write_text(dir / "short.json", doc.dump());
  check_rejected(run_xshell("relax run.json --init short.json", dir.path()), dir.path(),
                 {"short.json: malformed state file"});
  // A number that is not one (nlohmann writes NaN as null).
  doc = nlohmann::json::parse(state);
  doc["segments"][0]["thetas"][1] = nullptr;
  write_text(dir / "null.json", doc.dump());
  check_rejected(run_xshell("relax run.json --init null.json", dir.path()), dir.path(),
                 {"null.json: segments[0].thetas[1]: expected a number, got null"});
  fs::create_directory(dir / "folder.json");
  check_rejected(run_xshell("relax run.json --init folder.json", dir.path()), dir.path(),
                 {"folder.json: cannot read the state file: it is a folder"});
}

}  // namespace xshell::test
