#include "deployment_plot.hpp"

#include <dlfcn.h>
#include <pthread.h>
#include <unistd.h>

#include <csignal>
#include <future>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "child_process.hpp"

namespace xshell {

namespace {

namespace fs = std::filesystem;

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
  if (dladdr(reinterpret_cast<void*>(&plot_labels), &info) != 0 && info.dli_fname)
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

struct DeploymentPlotter::Impl {
  fs::path script, csv, png;
  PlotLabels labels;
  std::promise<bool> decision;  // draw or not
  bool decided = false;
  PlotOutcome outcome;  // written by the worker before it ends
  std::thread worker;
  bool finished = false;

  // The worker: a python3 that has loaded matplotlib ("ready"), waiting
  // for the decision on its input.
  void run() {
    sigset_t pipe_signal;  // a child that closed its input: EPIPE, not SIGPIPE
    sigemptyset(&pipe_signal);
    sigaddset(&pipe_signal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_signal, nullptr);
    if (script.empty()) script = find_script();
    std::error_code error;
    if (script.empty() || !fs::is_regular_file(script, error)) {
      outcome.message = "plot_deployment.py was not found beside the xshell program";
      return;
    }
    const fs::path temporary = png.parent_path() / ("." + png.filename().string() + ".tmp-" +
                                                    std::to_string(getpid()) + "-plot.png");
    // Debian's python first, where python3-matplotlib installs: a python3
    // earlier on PATH can be another without it (pyenv's shims took
    // 0.2-0.3 s to fail here, on the run's critical path).
    for (const char* python : {"/usr/bin/python3", "python3"}) {
      ChildProcess child({python, script.string(), "--wait", csv.string(), png.string(),
                          temporary.string(), labels.energy, labels.torque},
                         environment_with("MPLBACKEND", "Agg"));
      if (!child.running() || child.read_line() != "ready") continue;
      const bool draw = decision.get_future().get();
      child.write(draw ? "draw\n" : "skip\n");
      const int status = child.wait();
      std::error_code ignored;
      if (!draw) return;
      if (status != 0) {
        fs::remove(temporary, ignored);
        outcome.message = std::string(python) + " failed to draw the plot";
        return;
      }
      outcome.written = fs::exists(png, ignored);
      if (!outcome.written) outcome.message = std::string(python) + " did not write the plot";
      return;
    }
    outcome.message = "no python3 with matplotlib found (Debian package python3-matplotlib)";
  }
};

DeploymentPlotter::DeploymentPlotter(fs::path csv, fs::path png, UnitNames units, fs::path script)
    : impl_(std::make_unique<Impl>()) {
  impl_->script = std::move(script);
  impl_->csv = std::move(csv);
  impl_->png = std::move(png);
  impl_->labels = plot_labels(units);
  impl_->worker = std::thread([impl = impl_.get()] { impl->run(); });
}

DeploymentPlotter::~DeploymentPlotter() { finish(false); }

void DeploymentPlotter::start(bool draw) {
  Impl& s = *impl_;
  if (s.decided) return;
  s.decided = true;
  s.decision.set_value(draw);  // unread when the worker found no python
}

PlotOutcome DeploymentPlotter::finish(bool draw) {
  Impl& s = *impl_;
  start(draw);
  if (!s.finished) {
    s.finished = true;
    s.worker.join();
  }
  return s.outcome;
}

}  // namespace xshell
