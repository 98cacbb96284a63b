#include "deployment_plot.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <system_error>

namespace xshell {

namespace {

// argv: table, picture, temporary picture (renamed onto the picture).
constexpr const char* kScript = R"PY(
import csv, math, os, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

table, picture, temporary = sys.argv[1:4]
with open(table, newline="") as f:
    rows = list(csv.DictReader(f))
angle = [math.degrees(float(r["average_angle"])) for r in rows]
fig, left = plt.subplots(figsize=(8, 5), dpi=120)
for key, style, label in (("energy_total", "o-", "total"), ("energy_bending", "--", "bending"),
                          ("energy_twisting", ":", "twisting"), ("energy_stretching", "-.", "stretching")):
    left.plot(angle, [float(r[key]) for r in rows], style, color="tab:blue", label=label,
              markersize=3, linewidth=1.5 if key == "energy_total" else 1.0)
left.set_xlabel("average opening angle (degrees)")
left.set_ylabel("energy", color="tab:blue")
left.legend(loc="upper left", title="energy")
right = left.twinx()
right.plot(angle, [float(r["torque"]) for r in rows], "s-", color="tab:red", markersize=3)
unstable = [(a, float(r["torque"])) for a, r in zip(angle, rows) if r["stable"] != "true"]
if unstable:
    right.plot(*zip(*unstable), "x", color="black", label="not stable")
    right.legend(loc="lower right")
right.set_ylabel("torque dE/dA (energy per radian)", color="tab:red")
left.set_title("deployment")
fig.tight_layout()
fig.savefig(temporary, format="png")
os.replace(temporary, picture)
)PY";

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The first interpreter that imports matplotlib, or "".
std::string find_python() {
  for (const char* candidate : {"python3", "/usr/bin/python3"}) {
    const std::string probe = std::string(candidate) + " -c 'import matplotlib' >/dev/null 2>&1";
    const int status = std::system(probe.c_str());
    if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0) return candidate;
  }
  return "";
}

}  // namespace

PlotOutcome plot_deployment(const std::filesystem::path& csv, const std::filesystem::path& png) {
  PlotOutcome outcome;
  const std::string python = find_python();
  if (python.empty()) {
    outcome.message = "no python3 with matplotlib found (Debian package python3-matplotlib)";
    return outcome;
  }
  const std::filesystem::path temporary =
      png.parent_path() /
      ("." + png.filename().string() + ".tmp-" + std::to_string(getpid()) + "-plot.png");
  const std::string command = "MPLBACKEND=Agg " + python + " - " + quoted(csv.string()) + " " +
                              quoted(png.string()) + " " + quoted(temporary.string()) +
                              " >/dev/null 2>&1";
  // A python that exits early must not kill us with SIGPIPE.
  const auto previous = std::signal(SIGPIPE, SIG_IGN);
  FILE* pipe = popen(command.c_str(), "w");
  if (!pipe) {
    std::signal(SIGPIPE, previous);
    outcome.message = "cannot start " + python;
    return outcome;
  }
  const std::string script = kScript;
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int status = pclose(pipe);
  std::signal(SIGPIPE, previous);
  std::error_code ignored;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::filesystem::remove(temporary, ignored);
    outcome.message = python + " failed to draw the plot";
    return outcome;
  }
  outcome.written = std::filesystem::exists(png, ignored);
  if (!outcome.written) outcome.message = python + " did not write the plot";
  return outcome;
}

}  // namespace xshell
