// What a run says about how it ended, through the real program: an output
// failure is status 4 naming the file, and its summary says so (not
// "interrupted"); a model that is hard to draw is no output failure;
// stability is claimed only for converged states; an empty path is a usage
// error.
#include <doctest/doctest.h>

#include "reliability_support.hpp"

namespace xshell::test {

namespace {

// The sample's configuration (supports and loads: Newton iterates a few
// times) writing to "out" beside it.
void write_sample(const ScratchDirectory& dir, const std::string& extra = "") {
  write_text(dir / "run.json", sample_config("out", extra));
}

}  // namespace

TEST_CASE("run outcome: a step file that cannot be written stops the run with status 4") {
  ScratchDirectory dir("outcome-step-blocked");
  write_sample(dir);
  // A folder where the third step's rods file goes: steps 0 and 1 are
  // written, step 2 fails.
  fs::create_directories(dir / "out" / "rods_000002.vtp" / "keep");
  const CommandResult r = run_xshell("relax run.json --quiet", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 4);
  CHECK(last_line(r.errors) == "xshell: error: cannot write 'out/rods_000002.vtp': Is a directory");
  // Before: status "interrupted", reason "stop flag raised", while
  // "interrupted" was false.
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["status"] == "output_failed");
  CHECK(s["reason"] ==
        "stopped: an output could not be written: cannot write 'out/rods_000002.vtp': Is a "
        "directory");
  CHECK(s["interrupted"] == false);
  CHECK(s["converged"] == false);
  CHECK(s["stable"].is_null());
  // Step 2's files are written beside the next iteration (run_outputs.hpp):
  // its failure stops the run at iteration 3.
  CHECK(s["iterations"].get<long>() == 3);
  // The last good state is there, and no engineering result of a run that
  // did not finish.
  CHECK(read_json(dir / "out" / "state.json")["format"] == "xshell-state");
  CHECK_FALSE(fs::exists(dir / "out" / "stresses.vtp"));
  CHECK(temporary_files(dir / "out").empty());
}

TEST_CASE("run outcome: a full disk (file size limit) is status 4 naming the first file and why") {
  ScratchDirectory dir("outcome-full");
  write_sample(dir);
  // A file size limit of 8 KiB fails writes as a full disk does (with
  // "File too large" instead of "No space left on device"); SIGXFSZ ignored
  // as a batch system's limit would be. Before, the message did not say why
  // (and a converged run named a later file, modes.vtp, not the first that
  // failed).
  const std::string binary = XSHELL_BINARY;
  const std::string command = "cd '" + dir.path().string() +
                              "' && sh -c \"trap '' XFSZ; ulimit -f 8; exec '" + binary +
                              "' relax run.json --quiet\" > /dev/null 2> stderr.txt";
  const int raw = std::system(command.c_str());
  REQUIRE(WIFEXITED(raw));
  const std::string errors = read_text(dir / "stderr.txt");
  CAPTURE(errors);
  CHECK(WEXITSTATUS(raw) == 4);
  const std::string line = last_line(errors);
  CHECK(line.rfind("xshell: error: cannot write 'out/", 0) == 0);
  CHECK(contains(line, "_000000.vtp': "));  // the first step's files
  CHECK(contains(line, "File too large"));
  CHECK(count_lines(errors) == 1);
  CHECK(temporary_files(dir / "out").empty());
  // Whatever was written under a final name is complete.
  check_outputs_complete(dir / "out");
}

TEST_CASE("run outcome: an edge of 3e-12 is drawn, and is no output failure") {
  ScratchDirectory dir("outcome-short-edge");
  // Vertex 3 is 3e-12 above vertex 2 (the linkage is 1.4 across). Before,
  // the solids' sweep refused the edge, the run exited 4 ("rod 1: edge 2
  // has zero length", no file named) and the summary said "interrupted".
  write_text(dir / "short.obj", "v 0 0 0\nv 1 0 0\nv 1 3e-12 0\nv 2 1 0\nl 1 2 3 4\n");
  write_text(dir / "run.json", config_with("short.obj"));
  const CommandResult r = run_xshell("relax run.json --quiet", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status != 4);
  CHECK_FALSE(contains(r.errors, "zero length"));
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["status"] != "interrupted");
  CHECK(s["status"] != "output_failed");
  CHECK(fs::exists(dir / "out" / "solids_000000.vtp"));
  CHECK(check_outputs_complete(dir / "out") >= 6);
}

TEST_CASE("run outcome: a run that did not converge claims no stability") {
  ScratchDirectory dir("outcome-not-converged");
  write_sample(dir, R"(, "solver": {"max_iterations": 1})");
  const CommandResult r = run_xshell("relax run.json --quiet", dir.path());
  CAPTURE(r.errors);
  CHECK(r.status == 3);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["status"] == "max_iterations");
  // Before: the final factorization's verdict (true here), as if it were an
  // equilibrium.
  CHECK(s["stable"].is_null());
  CHECK(contains(last_line(r.errors), "stability not checked (not converged)"));
  // The same run converged: stable, a boolean.
  write_sample(dir);
  const CommandResult again = run_xshell("relax run.json --quiet", dir.path());
  CHECK(again.status == 0);
  CHECK(read_json(dir / "out" / "summary.json")["stable"] == true);
}

TEST_CASE("run outcome: an empty file or folder name on the command line is a usage error") {
  ScratchDirectory dir("outcome-empty-path");
  write_sample(dir);
  struct Case {
    std::string args, words;
  };
  const std::vector<Case> cases = {
      {"relax run.json --out ''", "relax: --out: must name a file or folder"},
      {"relax run.json --init ''", "relax: --init: must name a file or folder"},
      {"relax ''", "relax: config: must name a file or folder"},
      {"fabricate run.json --out ''", "fabricate: --out: must name a file or folder"},
      {"render out --out ''", "render: --out: must name a file or folder"},
  };
  int checked = 0;
  for (const Case& c : cases) {
    CAPTURE(c.args);
    // Before, `--out ''` ended in "internal error: filesystem error" (1).
    const CommandResult r = run_xshell(c.args, dir.path());
    CAPTURE(r.errors);
    CHECK(r.status == 2);
    CHECK(r.errors.rfind("xshell: error: " + c.words, 0) == 0);
    CHECK(count_lines(r.errors) == 1);
    CHECK_FALSE(fs::exists(dir / "out"));
    ++checked;
  }
  CHECK(checked == 5);
}

}  // namespace xshell::test
