// Interruptions through the real program: SIGINT or SIGTERM stops a run at
// the next iteration with the last good state, a summary saying it was
// interrupted and a closed series (exit status 130); SIGKILL, which cannot
// be caught, still never leaves a truncated file under a final name.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "reliability_support.hpp"

namespace xshell::test {

namespace {

// Slow enough to interrupt: damped dynamics with fictitious masses.
std::string slow_dynamics(const ScratchDirectory& dir) {
  return sample_config(
      dir / "out",
      R"(, "solver": {"method": "dynamics", "mass": "fictitious", "max_steps": 1000000})");
}

// Slow enough to interrupt: Newton iterating on a linkage that can slide
// away (three z rollers and a horizontal force: no equilibrium exists).
std::string endless_newton() {
  return config_with(grid_obj(), R"(, "solver": {"max_iterations": 1000000},
  "supports": [{"vertex": 0, "fix": ["z"]}, {"vertex": 5, "fix": ["z"]}, {"vertex": 27, "fix": ["z"]}],
  "loads": {"forces": [{"vertex": 13, "force": [1, 0, 0]}]})");
}

// Starts `config` in `dir`, waits for the 4th written step, sends `number`
// and checks the interrupted run's outputs. Returns the summary.
nlohmann::json interrupt(const ScratchDirectory& dir, const std::string& config, int number,
                         const std::string& wait_for = "rods_000003.vtp") {
  write_text(dir / "run.json", config);
  RelaxProcess run(dir / "run.json", dir.path());
  REQUIRE(run.started());
  REQUIRE(run.wait_for(dir / "out" / wait_for));
  run.signal(number);
  const int raw = run.wait();
  INFO("stderr: " << run.errors());
  REQUIRE(raw != -1);
  REQUIRE(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 130);
  const std::string line = last_line(run.errors());
  CHECK(line.rfind("xshell: interrupted after ", 0) == 0);
  CHECK(contains(line, "interrupted by a signal"));

  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["interrupted"] == true);
  CHECK(s["status"] == "interrupted");
  CHECK(s["reason"] == "interrupted by a signal");
  CHECK(s["converged"] == false);
  CHECK(std::isfinite(s["energy"]["total"].get<double>()));
  CHECK(read_json(dir / "out" / "state.json")["format"] == "xshell-state");
  // The series is closed and names every step file there is; every file is
  // complete and none is left under a temporary name.
  const std::string pvd = read_text(dir / "out" / "series.pvd");
  int steps = 0;
  for (const auto& entry : fs::directory_iterator(dir / "out"))
    if (entry.path().extension() == ".vtp") {
      CHECK_MESSAGE(contains(pvd, "file=\"" + entry.path().filename().string() + "\""),
                    "not in series.pvd: " << entry.path().filename());
      ++steps;
    }
  CHECK(steps >= 4);
  CHECK(check_outputs_complete(dir / "out") >= steps + 3);
  CHECK(temporary_files(dir / "out").empty());
  return s;
}

}  // namespace

TEST_CASE("interrupt: SIGTERM during damped dynamics") {
  ScratchDirectory dir("sigterm-dynamics");
  const nlohmann::json s = interrupt(dir, slow_dynamics(dir), SIGTERM);
  CHECK(s["solver"] == "dynamics");
  CHECK(s["iterations"].get<int>() >= 3);
}

TEST_CASE("interrupt: SIGINT during damped dynamics") {
  ScratchDirectory dir("sigint-dynamics");
  const nlohmann::json s = interrupt(dir, slow_dynamics(dir), SIGINT);
  CHECK(s["iterations"].get<int>() >= 3);
}

TEST_CASE("interrupt: SIGTERM and SIGINT during Newton, the state restarts the run") {
  for (const int number : {SIGTERM, SIGINT}) {
    CAPTURE(number);
    ScratchDirectory dir("signal-newton");
    const nlohmann::json s = interrupt(dir, endless_newton(), number);
    CHECK(s["solver"] == "newton");
    CHECK(s["iterations"].get<int>() >= 3);
    // The written state is the one the summary describes: a restart from it
    // (one iteration, then the limit) starts at the summary's energy.
    write_text(dir / "again.json", config_with(grid_obj(), R"(, "solver": {"max_iterations": 1},
  "supports": [{"vertex": 0, "fix": ["z"]}, {"vertex": 5, "fix": ["z"]}, {"vertex": 27, "fix": ["z"]}],
  "loads": {"forces": [{"vertex": 13, "force": [1, 0, 0]}]})"));
    const CommandResult again =
        run_xshell("relax again.json --init out/state.json --out again", dir.path());
    CAPTURE(again.errors);
    CHECK(again.status == 3);
    CHECK(read_json(dir / "again" / "summary.json")["history"][0]["energy"].get<double>() ==
          doctest::Approx(s["energy"]["total"].get<double>()).epsilon(1e-9));
  }
}

TEST_CASE("interrupt: SIGINT during a deployment") {
  ScratchDirectory dir("sigint-deployment");
  const nlohmann::json s = interrupt(
      dir,
      config_with(grid_obj(), R"(, "deployment": {"average_opening_angle": 1.2, "steps": 400})"),
      SIGINT, "rods_000004.vtp");
  REQUIRE(s.contains("deployment"));
  CHECK(s["deployment"]["status"] == "interrupted");
  // Every step in the table is complete: all twelve columns.
  const std::string table = read_text(dir / "out" / "deployment.csv");
  int rows = 0;
  std::size_t start = table.find('\n') + 1;
  for (std::size_t end = table.find('\n', start); end != std::string::npos;
       end = table.find('\n', start)) {
    const std::string row = table.substr(start, end - start);
    CHECK(std::count(row.begin(), row.end(), ',') == 11);
    ++rows;
    start = end + 1;
  }
  CHECK(start == table.size());  // ends with a complete line
  CHECK(rows >= 4);
}

TEST_CASE("interrupt: SIGKILL at any moment leaves no truncated file under a final name") {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> pause_ms(0, 40);
  int killed = 0, files = 0;
  for (const char* step :
       {"rods_000001.vtp", "rods_000004.vtp", "frames_000006.vtp", "joints_000009.vtp"}) {
    CAPTURE(step);
    ScratchDirectory dir("sigkill");
    write_text(dir / "run.json", slow_dynamics(dir));
    RelaxProcess run(dir / "run.json", dir.path());
    REQUIRE(run.started());
    REQUIRE(run.wait_for(dir / "out" / step));
    std::this_thread::sleep_for(std::chrono::milliseconds(pause_ms(rng)));
    run.signal(SIGKILL);
    const int raw = run.wait();
    REQUIRE(raw != -1);
    CHECK(WIFSIGNALED(raw));
    killed += WIFSIGNALED(raw) ? 1 : 0;
    files += check_outputs_complete(dir / "out");
    // No summary claims anything: the run never finished.
    CHECK_FALSE(fs::exists(dir / "out" / "summary.json"));
  }
  CHECK(killed == 4);
  CHECK(files >= 4 * 5);
}

TEST_CASE("interrupt: a closed stderr (SIGPIPE) does not stop a run before its outputs") {
  ScratchDirectory dir("sigpipe");
  write_text(dir / "run.json", sample_config(dir / "out"));
  int fds[2];
  REQUIRE(pipe(fds) == 0);
  close(fds[0]);  // nobody reads: every write to stderr fails
  const std::string binary = XSHELL_BINARY, config = (dir / "run.json").string();
  char* argv[] = {const_cast<char*>(binary.c_str()), const_cast<char*>("relax"),
                  const_cast<char*>(config.c_str()), const_cast<char*>("--verbose"), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  REQUIRE(spawned == 0);
  int raw = 0;
  REQUIRE(waitpid(pid, &raw, 0) == pid);
  CHECK_FALSE(WIFSIGNALED(raw));
  REQUIRE(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 0);
  CHECK(read_json(dir / "out" / "summary.json")["converged"] == true);
  CHECK(check_outputs_complete(dir / "out") >= 6);
}

TEST_CASE("interrupt: past the grace period the last written step's state is saved at once") {
  ScratchDirectory dir("interrupt-grace");
  // --grace 0: the run may not finish the iteration in progress (on a large
  // linkage one takes minutes: before, SIGTERM waited for it). Whichever
  // comes first, the iteration's end or the grace period's, the run ends
  // with status 130, a summary that says "interrupted" and a state that
  // --init accepts.
  write_text(dir / "run.json", endless_newton());
  RelaxProcess run(dir / "run.json", dir.path(), {"--grace", "0"});
  REQUIRE(run.started());
  REQUIRE(run.wait_for(dir / "out" / "rods_000003.vtp"));
  const auto sent = std::chrono::steady_clock::now();
  run.signal(SIGTERM);
  const int raw = run.wait();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  INFO("stderr: " << run.errors());
  REQUIRE(WIFEXITED(raw));
  CHECK(WEXITSTATUS(raw) == 130);
  CHECK(seconds < 5.0);
  const std::string line = last_line(run.errors());
  CHECK(line.rfind("xshell: interrupted", 0) == 0);
  const nlohmann::json s = read_json(dir / "out" / "summary.json");
  CHECK(s["status"] == "interrupted");
  CHECK(s["interrupted"] == true);
  CHECK(contains(s["reason"], "interrupted by a signal"));
  CHECK(std::isfinite(s["energy"]["total"].get<double>()));
  CHECK(check_outputs_complete(dir / "out") >= 6);
  // A step that the solver began while the state was being saved is not
  // written (a temporary file left by the write in flight at the exit).
  std::string leftovers;
  for (const std::string& name : temporary_files(dir / "out")) leftovers += name + " ";
  CHECK_MESSAGE(leftovers.empty(), "temporary files left: " << leftovers);
  write_text(dir / "again.json", config_with(grid_obj(), R"(, "solver": {"max_iterations": 1})"));
  const CommandResult again =
      run_xshell("relax again.json --init out/state.json --out again --quiet", dir.path());
  CHECK(again.status != 2);  // the saved state is a valid start
}

TEST_CASE("interrupt: --grace out of range is a usage error") {
  ScratchDirectory dir("interrupt-grace-usage");
  write_text(dir / "run.json", endless_newton());
  const CommandResult r = run_xshell("relax run.json --grace -1", dir.path());
  CHECK(r.status == 2);
  CHECK(r.errors.rfind("xshell: error: relax: --grace", 0) == 0);
  // NaN passes a range check (every comparison is false): before, it was
  // accepted and acted as --grace 0.
  for (const char* value : {"nan", "NaN", "-nan"}) {
    CAPTURE(value);
    // A configuration that does not exist: the usage error comes first
    // (before the fix, the run failed on the missing file instead).
    const CommandResult nan =
        run_xshell(std::string("relax missing.json --grace ") + value, dir.path());
    CHECK(nan.status == 2);
    CHECK(nan.errors.rfind("xshell: error: relax: --grace", 0) == 0);
    CHECK(contains(nan.errors, "must be a finite number"));
    CHECK(count_lines(nan.errors) == 1);
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

}  // namespace xshell::test
