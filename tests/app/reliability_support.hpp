// Helpers of the reliability tests (bad input, failing solves, signals):
// runs without root's privileges, a process to interrupt, and checks that
// every output under a final name is complete.
#pragma once

#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <thread>
#include <vector>

#include "command_runner.hpp"

extern char** environ;

namespace xshell::test {

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

inline int count_lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// The last line of `text` (without its newline).
inline std::string last_line(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  const std::size_t at = t.rfind('\n');
  return at == std::string::npos ? t : t.substr(at + 1);
}

// The sample's material with a linkage file and `extra` keys of the test's
// own, writing to "out" beside the configuration.
inline std::string config_with(const std::string& linkage, const std::string& extra = "") {
  return R"({
  "linkage": ")" +
         linkage + R"(",
  "subdivisions": 4,
  "rest_shape": "straight",
  "material": {"young_modulus": 2.0e10, "density": 1800,
               "cross_section": {"shape": "rectangle", "width": 0.01, "height": 0.007}},
  "output": {"directory": "out"})" +
         extra + R"(
})";
}

// The text of an OBJ file: a flat 3 x 3 grid of rods, spacing 0.25 m; every
// joint opens at pi/2.
inline std::string flat_grid_obj() {
  std::ostringstream o;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) o << "v " << 0.25 * j << " " << 0.25 * i << " 0\n";
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int v = i * 3 + j + 1;  // 1-based
      if (j + 1 < 3) o << "l " << v << " " << v + 1 << "\n";
      if (i + 1 < 3) o << "l " << v << " " << v + 3 << "\n";
    }
  return o.str();
}

// The bundled grid sample (absolute path).
inline std::string grid_obj() { return (fs::path(XSHELL_SAMPLES_DIR) / "grid.obj").string(); }

// Whether permission bits bind this process (not for root).
inline bool permissions_bind() { return ::geteuid() != 0; }

// Whether every folder from the root down to `dir` lets other users through
// (o+x): else nobody cannot even reach `dir`.
inline bool reachable_by_others(const fs::path& dir) {
  for (fs::path p = fs::absolute(dir); !p.empty(); p = p.parent_path()) {
    std::error_code error;
    const fs::perms perms = fs::status(p, error).permissions();
    if (error || (perms & fs::perms::others_exec) == fs::perms::none) return false;
    if (p == p.root_path()) break;
  }
  return true;
}

// Runs `xshell ARGS` in `dir` as an unprivileged user, so that permission
// bits bind: directly when the tests do not run as root, else through
// setpriv(1) as nobody (a copy of the program in `dir`, so that nobody can
// reach it; without LSAN_OPTIONS, whose suppressions file nobody may not
// be able to read). Nobody may not read the clone (a clone in root's home
// or in a folder made by mktemp -d): every file the run reads must be in
// `dir`, named relative to it. Returns status -2 and the reason in `errors`
// when such a run is not possible here.
inline CommandResult run_xshell_unprivileged(const std::string& args, const fs::path& dir) {
  if (permissions_bind()) return run_xshell(args, dir);
  if (std::system("command -v setpriv >/dev/null 2>&1") != 0)
    return {-2, "root without setpriv(1): no unprivileged run"};
  // The scratch folder itself is private (mkdtemp) and opened below.
  if (!reachable_by_others(fs::absolute(dir).parent_path()))
    return {-2, "the scratch folder " + dir.string() +
                    " is inside a folder other users cannot enter (TMPDIR?): no unprivileged run"};
  const fs::path copy = dir / "xshell-copy";
  fs::copy_file(XSHELL_BINARY, copy, fs::copy_options::overwrite_existing);
  fs::permissions(dir, fs::perms::all & ~fs::perms::group_write & ~fs::perms::others_write);
  const fs::path err = dir / "stderr.txt";
  const std::string command =
      "cd '" + dir.string() +
      "' && env -u LSAN_OPTIONS setpriv --reuid=65534 --regid=65534 --clear-groups "
      "./xshell-copy " +
      args + " > /dev/null 2> '" + err.string() + "'";
  const int raw = std::system(command.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.errors = read_text(err);
  fs::remove(copy);
  return r;
}

// Runs `xshell ARGS` in `dir` like run_xshell, killed after `seconds` (a run
// that blocks or reads forever then ends with status 137).
inline CommandResult run_xshell_limited(const std::string& args, const fs::path& dir, int seconds) {
  const fs::path err = dir / "stderr.txt";
  const std::string command = "cd '" + dir.string() + "' && timeout -s KILL " +
                              std::to_string(seconds) + " '" + std::string(XSHELL_BINARY) + "' " +
                              args + " > /dev/null 2> '" + err.string() + "'";
  const int raw = std::system(command.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.errors = read_text(err);
  return r;
}

// A running `xshell relax CONFIG --quiet [EXTRA...]` (stderr to
// `dir`/stderr.txt).
class RelaxProcess {
 public:
  RelaxProcess(const fs::path& config, const fs::path& dir,
               const std::vector<std::string>& extra = {})
      : errors_(dir / "stderr.txt") {
    const std::string binary = XSHELL_BINARY, path = config.string(), err = errors_.string();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> argv = {const_cast<char*>(binary.c_str()), const_cast<char*>("relax"),
                               const_cast<char*>(path.c_str()), const_cast<char*>("--quiet")};
    for (const std::string& argument : extra) argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    started_ = posix_spawn(&pid_, binary.c_str(), &actions, nullptr, argv.data(), environ) == 0;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~RelaxProcess() {
    if (started_ && !reaped_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  RelaxProcess(const RelaxProcess&) = delete;
  RelaxProcess& operator=(const RelaxProcess&) = delete;

  bool started() const { return started_; }
  // Waits (up to `limit`) until `file` exists; false when it never did or
  // the process ended first.
  bool wait_for(const fs::path& file, std::chrono::seconds limit = std::chrono::seconds(120)) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < deadline) {
      if (fs::exists(file)) return true;
      if (waitpid(pid_, &raw_, WNOHANG) == pid_) {
        reaped_ = true;
        return fs::exists(file);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  void signal(int number) { kill(pid_, number); }
  // Waits for the end; the raw wait status (-1 on failure or timeout).
  int wait(std::chrono::seconds limit = std::chrono::seconds(120)) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!reaped_ && std::chrono::steady_clock::now() < deadline) {
      if (waitpid(pid_, &raw_, WNOHANG) == pid_)
        reaped_ = true;
      else
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return reaped_ ? raw_ : -1;
  }
  std::string errors() const { return read_text(errors_); }

 private:
  fs::path errors_;
  pid_t pid_ = -1;
  bool started_ = false, reaped_ = false;
  int raw_ = 0;
};

// Checks that every output in `dir` under a final name is complete: JSON
// files parse, VTK XML files end with their closing tag, the series names
// only files that exist. Returns the number of files checked.
inline int check_outputs_complete(const fs::path& dir) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || name.front() == '.')
      continue;  // temporary names are never final
    const std::string text = read_text(entry.path());
    INFO("file: " << name);
    if (entry.path().extension() == ".json") {
      CHECK(nlohmann::json::accept(text));
      ++checked;
    } else if (entry.path().extension() == ".vtp" || entry.path().extension() == ".pvd") {
      std::string tail = text.substr(text.size() > 64 ? text.size() - 64 : 0);
      while (!tail.empty() && (tail.back() == '\n' || tail.back() == ' ')) tail.pop_back();
      CHECK(tail.size() >= 10);
      CHECK(tail.substr(tail.size() - std::min<std::size_t>(tail.size(), 10)) == "</VTKFile>");
      ++checked;
    }
  }
  if (fs::exists(dir / "series.pvd")) {
    const std::string pvd = read_text(dir / "series.pvd");
    for (std::size_t at = pvd.find("file=\""); at != std::string::npos;
         at = pvd.find("file=\"", at + 1)) {
      const std::size_t end = pvd.find('"', at + 6);
      const std::string file = pvd.substr(at + 6, end - at - 6);
      CHECK_MESSAGE(fs::exists(dir / file), "series.pvd names a missing file: " << file);
    }
  }
  return checked;
}

// Names of temporary files (".NAME.tmp-PID-N") left in `dir`.
inline std::vector<std::string> temporary_files(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name.front() == '.' && contains(name, ".tmp-")) out.push_back(name);
  }
  return out;
}

}  // namespace xshell::test
