#include "deployment_plot.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>
#include <vector>

extern char** environ;

namespace xshell {

namespace {

namespace fs = std::filesystem;

// Runs `argv` (argv[0] looked up on PATH) with MPLBACKEND=Agg added to the
// environment and its output discarded; returns whether it exited with 0.
bool run_quietly(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::string> env_strings = {"MPLBACKEND=Agg"};
  for (char** e = environ; *e != nullptr; ++e)
    if (std::string(*e).rfind("MPLBACKEND=", 0) != 0) env_strings.emplace_back(*e);
  std::vector<char*> env;
  for (std::string& e : env_strings) env.push_back(e.data());
  env.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return false;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return false;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// The first interpreter that imports matplotlib, or "".
std::string find_python() {
  for (const char* candidate : {"python3", "/usr/bin/python3"})
    if (run_quietly({candidate, "-c", "import matplotlib"})) return candidate;
  return "";
}

// plot_deployment.py beside this program (the build tree) or in
// ../share/xshell (an installation), or beside the shared object this code
// is part of (the Python module, build/python/xshell); "" when none exists.
fs::path find_script() {
  std::error_code error;
  std::vector<fs::path> folders;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error)
    folders = {program.parent_path(), program.parent_path().parent_path() / "share" / "xshell"};
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&plot_deployment), &info) != 0 && info.dli_fname)
    folders.push_back(fs::path(info.dli_fname).parent_path());
  for (const fs::path& folder : folders)
    if (fs::is_regular_file(folder / "plot_deployment.py", error))
      return folder / "plot_deployment.py";
  return {};
}

}  // namespace

PlotLabels plot_labels(const UnitNames& units) {
  if (units.length.empty() && units.force.empty())
    return {"energy", "torque dE/dA (energy per radian)"};
  return {"energy [" + unit_label("force length", units) + "]",
          "torque dE/dA [" + unit_label("force length/rad", units) + "]"};
}

PlotOutcome plot_deployment(const fs::path& csv, const fs::path& png, const UnitNames& units) {
  PlotOutcome outcome;
  const fs::path script = find_script();
  if (script.empty()) {
    outcome.message = "plot_deployment.py was not found beside the xshell program";
    return outcome;
  }
  const std::string python = find_python();
  if (python.empty()) {
    outcome.message = "no python3 with matplotlib found (Debian package python3-matplotlib)";
    return outcome;
  }
  const fs::path temporary = png.parent_path() / ("." + png.filename().string() + ".tmp-" +
                                                  std::to_string(getpid()) + "-plot.png");
  std::error_code ignored;
  const PlotLabels labels = plot_labels(units);
  if (!run_quietly({python, script.string(), csv.string(), png.string(), temporary.string(),
                    labels.energy, labels.torque})) {
    fs::remove(temporary, ignored);
    outcome.message = python + " failed to draw the plot";
    return outcome;
  }
  outcome.written = fs::exists(png, ignored);
  if (!outcome.written) outcome.message = python + " did not write the plot";
  return outcome;
}

}  // namespace xshell
