// The output folder through the real program: a second writer is refused,
// an earlier run's files do not survive into a new run's folder, and no
// input is ever overwritten by an output.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "bad_input_support.hpp"

namespace xshell::test {

namespace {

// The highest step number among the folder's rods_NNNNNN.vtp (-1: none).
int last_step(const fs::path& dir) {
  int last = -1;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("rods_", 0) == 0 && entry.path().extension() == ".vtp")
      last = std::max(last, std::stoi(name.substr(5, 6)));
  }
  return last;
}

}  // namespace

TEST_CASE("output folder: a re-run leaves none of the earlier run's files") {
  ScratchDirectory dir("folder-rerun");
  write_text(dir / "run.json", sample_config("out"));
  const CommandResult first = run_xshell("relax run.json --quiet", dir.path());
  REQUIRE(first.status == 0);
  const int first_last = last_step(dir / "out");
  REQUIRE(first_last >= 3);
  CHECK(fs::exists(dir / "out" / "stresses.vtp"));
  // A file of the user's own, and a leftover step of some older, longer run.
  write_text(dir / "out" / "notes.txt", "mine");
  write_text(dir / "out" / "solids_000099.vtp", "old");
  // The same run stopped after one iteration: before, steps 2.. of the
  // first run stayed, and `render out` drew the first run's final state.
  write_text(dir / "short.json", sample_config("out", R"(, "solver": {"max_iterations": 1})"));
  const CommandResult second = run_xshell("relax short.json --quiet", dir.path());
  CAPTURE(second.errors);
  REQUIRE(second.status == 3);
  CHECK(last_step(dir / "out") == 1);
  CHECK_FALSE(fs::exists(dir / "out" / "solids_000099.vtp"));
  CHECK_FALSE(fs::exists(dir / "out" / "rods_000002.vtp"));
  // Engineering results belong to converged runs only: the first run's go.
  CHECK_FALSE(fs::exists(dir / "out" / "stresses.vtp"));
  CHECK_FALSE(fs::exists(dir / "out" / "fabrication.csv"));
  CHECK(read_text(dir / "out" / "notes.txt") == "mine");
  CHECK(read_json(dir / "out" / "summary.json")["status"] == "max_iterations");
  CHECK(check_outputs_complete(dir / "out") >= 8);
}

TEST_CASE("output folder: a second run writing the same folder at once is refused") {
  ScratchDirectory dir("folder-locked");
  write_text(dir / "run.json", sample_config("out"));
  REQUIRE(run_xshell("relax run.json --quiet", dir.path()).status == 0);
  const std::string summary = read_text(dir / "out" / "summary.json");
  // Another run holds the folder (as xshell does while it writes).
  const int fd = ::open((dir / "out" / ".xshell-lock").c_str(), O_RDWR | O_CREAT, 0644);
  REQUIRE(fd >= 0);
  REQUIRE(::flock(fd, LOCK_EX | LOCK_NB) == 0);
  // Before: both exited 0, their files mixed.
  const CommandResult r = run_xshell("relax run.json --quiet", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 4);
  CHECK(count_lines(r.errors) == 1);
  CHECK(contains(r.errors, "another xshell run is writing to this output directory"));
  CHECK(read_text(dir / "out" / "summary.json") == summary);  // untouched
  const CommandResult fabricate = run_xshell("fabricate run.json", dir.path());
  CHECK(fabricate.status == 4);
  ::close(fd);  // released: the folder is free again
  CHECK(run_xshell("relax run.json --quiet", dir.path()).status == 0);
}

TEST_CASE("output folder: a run started while another writes the folder is refused") {
  ScratchDirectory dir("folder-concurrent");
  // A slow run (kinetic damping, every reset written) and a second one.
  write_text(dir / "slow.json",
             sample_config("out", R"(, "solver": {"method": "kinetic-damping"})"));
  write_text(dir / "fast.json", sample_config("out"));
  RelaxProcess slow(dir / "slow.json", dir.path());
  REQUIRE(slow.started());
  REQUIRE(slow.wait_for(dir / "out" / "rods_000001.vtp"));
  const CommandResult fast = run_xshell("relax fast.json --quiet", dir.path());
  CAPTURE(fast.errors);
  CHECK(fast.status == 4);
  CHECK(contains(fast.errors, "another xshell run is writing to this output directory"));
  slow.signal(SIGTERM);
  const int raw = slow.wait();
  CHECK(WIFEXITED(raw));
  CHECK(read_json(dir / "out" / "summary.json")["solver"] == "kinetic-damping");
}

TEST_CASE("output folder: an input named like an output in the folder is refused, not replaced") {
  ScratchDirectory dir("folder-collision");
  fs::create_directories(dir / "out");
  fs::copy_file(grid_obj(), dir / "out" / "state.json");  // a linkage named state.json
  write_text(dir / "linkage.json", replacing(sample_config("out"), grid_obj(), "out/state.json"));
  const std::string linkage = read_text(dir / "out" / "state.json");
  // A configuration named summary.json writing to its own folder.
  write_text(dir / "summary.json", sample_config("."));
  // A state continued into the folder it came from.
  write_text(dir / "run.json", sample_config("done"));
  REQUIRE(run_xshell("relax run.json --quiet", dir.path()).status == 0);
  const std::string state = read_text(dir / "done" / "state.json");
  struct Case {
    std::string args, words;
    fs::path kept;
    std::string text;
  };
  const std::vector<Case> cases = {
      {"relax linkage.json", "the linkage 'out/state.json' is in the output directory",
       dir / "out" / "state.json", linkage},
      {"relax summary.json", "the configuration 'summary.json' is in the output directory",
       dir / "summary.json", read_text(dir / "summary.json")},
      {"relax run.json --init done/state.json --out done",
       "the --init state 'done/state.json' is in the output directory", dir / "done" / "state.json",
       state},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.args);
    // Before: each input silently overwritten by the run's output.
    const CommandResult r = run_xshell(c.args + " --quiet", dir.path());
    CAPTURE(r.errors);
    CHECK(r.status == 2);
    CHECK(count_lines(r.errors) == 1);
    CHECK(r.errors.rfind("xshell: error: " + c.words, 0) == 0);
    CHECK(read_text(c.kept) == c.text);
    ++checked;
  }
  CHECK(checked == 3);
  // A link to an output under another name is the same file.
  fs::create_symlink(dir / "done" / "state.json", dir / "link.json");
  const CommandResult link = run_xshell("relax run.json --init link.json --out done", dir.path());
  CHECK(link.status == 2);
  CHECK(contains(link.errors, "is the output file 'state.json'"));
  CHECK(read_text(dir / "done" / "state.json") == state);
}

TEST_CASE("output folder: a long run keeps at most output.max_steps VTK steps, and says so") {
  ScratchDirectory dir("folder-max-steps");
  // Kinetic damping writes a step at every reset (26 here); before, a
  // million iterations wrote thousands of steps without a word (129 MB
  // after 998 steps of a deployment).
  write_text(dir / "run.json",
             replacing(sample_config("out", R"(, "solver": {"method": "kinetic-damping"})"),
                       "\"directory\": \"out\"", "\"directory\": \"out\", \"max_steps\": 8"));
  const CommandResult r = run_xshell("relax run.json --quiet", dir.path());
  CAPTURE(r.errors);
  REQUIRE(r.status == 0);
  CHECK(contains(r.errors,
                 "xshell: warning: the VTK series reached its 8 steps "
                 "(output.max_steps): every other step removed, 1 in 2 written"));
  int steps = 0;
  for (const auto& entry : fs::directory_iterator(dir / "out"))
    steps += entry.path().filename().string().rfind("rods_", 0) == 0 ? 1 : 0;
  CHECK(steps >= 2);
  CHECK(steps < 8);
  CHECK(fs::exists(dir / "out" / "rods_000000.vtp"));  // the start stays
  CHECK(check_outputs_complete(dir / "out") >= 4 * steps);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["configuration"]["output"]["max_steps"] == 8);
  // 1 is no limit that can be kept (the first and the latest step).
  write_text(dir / "one.json", replacing(sample_config("out"), "\"directory\": \"out\"",
                                         "\"directory\": \"out\", \"max_steps\": 1"));
  const CommandResult one = run_xshell("relax one.json", dir.path());
  CHECK(one.status == 2);
  CHECK(contains(one.errors, "output.max_steps: must be 0 (no limit) or at least 2, got 1"));
}

}  // namespace xshell::test
