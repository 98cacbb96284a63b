// Files through the real program: inputs that are no regular files or too
// large (exit status 2, one line naming the file), and outputs that cannot be
// written (exit status 4).
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <algorithm>
#include <functional>

#include "bad_input_support.hpp"
#include "skip.hpp"

namespace xshell::test {

// ---------------------------------------------------------------------------
// What is read, and how much: files that are no regular files, sizes,
// nesting, coordinates, and messages that stay one short line

TEST_CASE("bad input: a FIFO or a device as configuration or linkage or state is refused at once") {
  ScratchDirectory dir("not-regular");
  REQUIRE(::mkfifo((dir / "fifo.json").c_str(), 0600) == 0);
  REQUIRE(::mkfifo((dir / "fifo.obj").c_str(), 0600) == 0);
  write_text(dir / "fifo_linkage.json", config_with("fifo.obj"));
  write_text(dir / "zero_linkage.json", config_with("/dev/zero"));
  write_text(dir / "run.json", grid_config());
  struct Case {
    std::string args, words;
  };
  const std::vector<Case> cases = {
      {"relax fifo.json", "cannot open configuration file 'fifo.json': it is a FIFO"},
      {"relax /dev/zero", "cannot open configuration file '/dev/zero': it is a device"},
      {"relax fifo_linkage.json", "cannot open linkage file 'fifo.obj': it is a FIFO"},
      {"relax zero_linkage.json", "cannot open linkage file '/dev/zero': it is a device"},
      {"relax run.json --init fifo.json", "fifo.json: cannot read the state file: it is a FIFO"},
      {"relax run.json --init /dev/zero", "/dev/zero: cannot read the state file: it is a device"},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.args);
    // Before, each blocked (a FIFO without a writer) or read without end.
    check_rejected(run_xshell_limited(c.args, dir.path(), 5), dir.path(), {c.words});
    ++checked;
  }
  CHECK(checked == 6);
}

TEST_CASE("bad input: a // comment in the configuration gives its true position") {
  ScratchDirectory dir("config-comment");
  check_rejected(relax_config(dir, "// settings\n" + grid_config()), dir.path(),
                 {"run.json:1:1: invalid JSON", "JSON has no comments"});
  check_rejected(relax_config(dir, grid_config_replacing("\"subdivisions\": 4,",
                                                         "\"subdivisions\": 4, // more?")),
                 dir.path(), {"run.json:3:22: invalid JSON", "JSON has no comments"});
}

TEST_CASE("bad input: a configuration nested too deep is refused at once") {
  ScratchDirectory dir("config-nested");
  // 1.2 MB nested in a key: before, 83 s and 10.6 GB to be rejected.
  const int depth = 100000;
  std::string text = R"({"linkage": "grid.obj", "material": )";
  for (int i = 0; i < depth; ++i) text += R"({"young_modulus": )";
  text += "1" + std::string(depth, '}') + "}";
  write_text(dir / "run.json", text);
  check_rejected(run_xshell_limited("relax run.json", dir.path(), 20), dir.path(),
                 {"run.json: material.young_modulus.young_modulus", "nested deeper than 64"});
  write_text(dir / "run.json", std::string(200000, '['));
  check_rejected(run_xshell_limited("relax run.json", dir.path(), 20), dir.path(),
                 {"run.json: [0][0]", "nested deeper than 64"});
}

TEST_CASE("bad input: a NUL byte in the OBJ or in a path is shown escaped") {
  ScratchDirectory dir("nul");
  const CommandResult obj =
      relax_obj(dir, std::string("v 0 0 0\nv 1 0\0 0\nv 1 1 0\nl 1 2 3\n", 32));
  check_rejected(obj, dir.path(), {"bad.obj:2: coordinate '0\\0' is not a number"});
  CHECK(obj.errors.find('\0') == std::string::npos);
  const CommandResult path = relax_config(dir, config_with("grid\\u0000.obj"));
  check_rejected(path, dir.path(),
                 {"run.json: linkage: a file name cannot contain a NUL byte", "grid\\0.obj"});
}

TEST_CASE("bad input: an OBJ with CR-only line endings is read line by line") {
  ScratchDirectory dir("obj-cr");
  std::string text = read_text(grid_obj());
  std::replace(text.begin(), text.end(), '\n', '\r');
  write_text(dir / "grid.obj", text);
  write_text(dir / "run.json", config_with("grid.obj"));
  const CommandResult r = run_xshell("relax run.json", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 0);
}

TEST_CASE("bad input: a long path is quoted shortened in one short line") {
  ScratchDirectory dir("long-path");
  const std::string path = std::string(1000000, 'p') + "/grid.obj";  // 1 MB
  const CommandResult r = relax_config(dir, config_with(path));
  check_rejected(r, dir.path(), {"cannot open linkage file '", "...", "/grid.obj'"});
  CHECK(r.errors.size() < 400);
}

TEST_CASE("bad input: coordinates near 1e300 or 1e-300 are refused with the reason") {
  ScratchDirectory dir("obj-extreme");
  check_rejected(relax_obj(dir, "v -5e299 0 0\nv 1.25e299 0 0\nv 0 1e299 0\nl 1 2 3\n"), dir.path(),
                 {"bad.obj:1: coordinate '-5e299' is outside the supported range"});
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1e-300 0 0\nv 1e-300 1e-300 0\nl 1 2 3\n"), dir.path(),
                 {"bad.obj: the linkage measures", "at least 1e-06"});
  // 1e-100: before, the run "converged" and then failed writing its outputs.
  check_rejected(relax_obj(dir, "v 0 0 0\nv 1e-100 0 0\nv 1e-100 1e-100 0\nl 1 2 3\n"), dir.path(),
                 {"bad.obj: the linkage measures"});
}

TEST_CASE("bad input: --init with a state xshell would not have written") {
  ScratchDirectory dir("init-invalid");
  write_text(dir / "run.json", grid_config());
  REQUIRE(run_xshell("relax run.json --out first", dir.path()).status == 0);
  const nlohmann::json state = read_json(dir / "first" / "state.json");
  struct Case {
    std::string name, words;
    std::function<void(nlohmann::json&)> change;
  };
  const std::vector<Case> cases = {
      {"frame.json", "frame.json: joints[0].reference_frame: not a rotation",
       [](nlohmann::json& s) {
         s["joints"][0]["reference_frame"][1] = {0.0, 0.6, 0.8};
       }},
      {"origin.json", "origin.json: origin: a coordinate beyond",
       [](nlohmann::json& s) {
         s["origin"] = {1e300, 0, 0};
       }},
      {"zero.json", "zero.json: segments[0].nodes: nodes 0 and 1 coincide",
       [](nlohmann::json& s) {
         for (auto& segment : s["segments"])
           for (auto& node : segment["nodes"]) node = {0.0, 0.0, 0.0};
       }},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.name);
    nlohmann::json changed = state;
    c.change(changed);
    write_text(dir / c.name, changed.dump());
    check_rejected(run_xshell("relax run.json --init " + c.name, dir.path()), dir.path(),
                   {c.words});
    ++checked;
  }
  CHECK(checked == 3);
  // The state as written restarts the run.
  CHECK(run_xshell("relax run.json --init first/state.json --out again", dir.path()).status == 0);
}

// ---------------------------------------------------------------------------
// Outputs that cannot be written: exit status 4

TEST_CASE("bad output: an output directory inside a file") {
  ScratchDirectory dir("out-under-file");
  write_text(dir / "a_file", "not a folder");
  const CommandResult r = relax_config(
      dir, grid_config_replacing("\"directory\": \"out\"", "\"directory\": \"a_file/out\""));
  CAPTURE(r.errors);
  CHECK(r.status == 4);
  CHECK(r.errors.rfind("xshell: error: ", 0) == 0);
  CHECK(contains(r.errors, "a_file"));
  CHECK(count_lines(r.errors) == 1);
}

TEST_CASE("bad output: an output directory that is a file") {
  ScratchDirectory dir("out-is-file");
  write_text(dir / "out", "not a folder");
  const CommandResult r = relax_config(dir, grid_config());
  CAPTURE(r.errors);
  CHECK(r.status == 4);
  CHECK(contains(r.errors, "out"));
  CHECK(read_text(dir / "out") == "not a folder");
}

TEST_CASE("bad output: a 300-character output folder name gives the system's reason") {
  ScratchDirectory dir("out-long-name");
  const std::string name(300, 'o');
  const CommandResult r = relax_config(
      dir, grid_config_replacing("\"directory\": \"out\"", "\"directory\": \"" + name + "\""));
  CAPTURE(r.errors);
  CHECK(r.status == 4);
  CHECK(r.errors.rfind("xshell: error: ", 0) == 0);
  CHECK(count_lines(r.errors) == 1);
  CHECK(contains(r.errors, "': File name too long"));
  CHECK(r.errors.size() < 400);  // the name quoted shortened
}

TEST_CASE("bad output: a read-only output directory") {
  ScratchDirectory dir("out-read-only");
  // The linkage beside the configuration: the unprivileged run may not be
  // able to read the clone's samples (a clone in a folder only its owner
  // can enter).
  fs::copy_file(grid_obj(), dir / "grid.obj");
  write_text(dir / "run.json", replacing(config_with("grid.obj"), "\"directory\": \"out\"",
                                         "\"directory\": \"locked/out\""));
  fs::create_directory(dir / "locked");
  fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec |
                                      fs::perms::group_read | fs::perms::group_exec |
                                      fs::perms::others_read | fs::perms::others_exec);
  const CommandResult r = run_xshell_unprivileged("relax run.json", dir.path());
  if (r.status == -2) XSHELL_SKIP(r.errors + ": the read-only case cannot be checked here");
  CAPTURE(r.errors);
  CHECK(r.status == 4);
  CHECK(contains(r.errors, "locked/out"));
  CHECK(contains(r.errors, "Permission denied"));
  CHECK(fs::is_empty(dir / "locked"));
}

TEST_CASE("bad output: a final output blocked after the solve (summary.json is a folder)") {
  ScratchDirectory dir("out-blocked");
  fs::create_directories(dir / "out" / "summary.json");
  const CommandResult r = relax_config(dir, grid_config());
  CAPTURE(r.errors);
  CHECK(r.status == 4);
  CHECK(contains(r.errors, "summary.json"));
  CHECK(last_line(r.errors).rfind("xshell: error: ", 0) == 0);
  // What could be written is complete; no temporary file is left.
  CHECK(check_outputs_complete(dir / "out") >= 4);
  CHECK(temporary_files(dir / "out").empty());
}

}  // namespace xshell::test
