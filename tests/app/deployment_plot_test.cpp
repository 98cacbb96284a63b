#include "app/deployment_plot.hpp"

#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "app/child_process.hpp"
#include "command_runner.hpp"
#include "skip.hpp"

namespace xshell::test {

namespace {

namespace fs = std::filesystem;

const fs::path kScript = fs::path(XSHELL_BINARY).parent_path() / "plot_deployment.py";

bool has_matplotlib() {
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    ChildProcess child({python, "-c", "import matplotlib"}, environment_with("MPLBACKEND", "Agg"));
    if (child.running() && child.wait() == 0) return true;
  }
  return false;
}

void write_table(const fs::path& path) {
  std::ofstream out(path);
  out << "step,average_angle,energy_total,energy_stretching,energy_bending,energy_twisting,"
         "torque,iterations,stable,min_opening_angle,max_opening_angle,factorizations\n"
         "0,1.0,2.0,0.5,1.0,0.5,3.0,4,true,0.9,1.1,5\n"
         "1,1.1,2.5,0.6,1.2,0.7,3.5,3,false,1.0,1.2,4\n";
}

}  // namespace

TEST_CASE("A child process: its input and output, its exit status, its own process group") {
  ChildProcess child({"sh", "-c", "read line; echo \"got $line\"; exit 7"},
                     environment_with("XSHELL_TEST", "1"));
  REQUIRE(child.running());
  CHECK(child.write("hello\n"));
  CHECK(child.read_line() == "got hello");
  CHECK(child.read_line() == "");  // the end of its output
  CHECK(child.wait() == 7);
  CHECK(child.wait() == 7);  // waited once

  ChildProcess group(
      {"sh", "-c", "read -r pid comm state ppid pgrp rest < /proc/$$/stat; echo $pgrp"},
      environment_with("XSHELL_TEST", "1"));
  REQUIRE(group.running());
  const std::string pgid = group.read_line();
  CHECK(std::stol(pgid) != static_cast<long>(getpgrp()));
  CHECK(group.wait() == 0);

  // The environment entry is set, replacing an inherited one.
  const std::vector<std::string> env = environment_with("PATH", "/nowhere");
  CHECK(std::count_if(env.begin(), env.end(),
                      [](const std::string& e) { return e.rfind("PATH=", 0) == 0; }) == 1);
  CHECK(std::find(env.begin(), env.end(), "PATH=/nowhere") != env.end());

  ChildProcess missing({"/nonexistent/program"}, env);
  CHECK_FALSE(missing.running());
  CHECK(missing.wait() == -1);
  CHECK(missing.read_line() == "");
  CHECK_FALSE(missing.write("x\n"));
}

TEST_CASE("A child that waits for its input ends when its pipe closes") {
  const auto start = std::chrono::steady_clock::now();
  {
    ChildProcess child({"sh", "-c", "read line; exit 0"}, environment_with("XSHELL_TEST", "1"));
    REQUIRE(child.running());
  }  // the destructor closes its input and waits
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
}

TEST_CASE("The deployment plot loads before the table exists and draws it once complete") {
  if (!has_matplotlib()) XSHELL_SKIP("no python3 with matplotlib: no deployment plot");
  REQUIRE(fs::is_regular_file(kScript));
  const ScratchDirectory scratch("deployment-plot");
  const fs::path& dir = scratch.path();
  {
    DeploymentPlotter plotter(dir / "table.csv", dir / "plot.png", {"mm", "N"}, kScript);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    write_table(dir / "table.csv");  // written while the plotter loads
    const PlotOutcome drawn = plotter.finish(true);
    CAPTURE(drawn.message);
    CHECK(drawn.written);
    CHECK(plotter.finish(false).written);  // the same outcome
  }
  CHECK(fs::file_size(dir / "plot.png") > 1000);
  // Not asked to draw: no picture, no message, no temporary left.
  {
    DeploymentPlotter plotter(dir / "table.csv", dir / "skipped.png", {}, kScript);
    const PlotOutcome skipped = plotter.finish(false);
    CHECK_FALSE(skipped.written);
    CHECK(skipped.message.empty());
  }
  // start() returns while matplotlib still loads; its decision holds.
  {
    DeploymentPlotter plotter(dir / "table.csv", dir / "started.png", {}, kScript);
    plotter.start(true);
    CHECK_FALSE(fs::exists(dir / "started.png"));
    CHECK(plotter.finish(false).written);
  }
  CHECK(fs::file_size(dir / "started.png") > 1000);
  { DeploymentPlotter destroyed(dir / "table.csv", dir / "destroyed.png", {}, kScript); }
  CHECK_FALSE(fs::exists(dir / "skipped.png"));
  CHECK_FALSE(fs::exists(dir / "destroyed.png"));
  // A table it cannot read: a message, no picture.
  DeploymentPlotter broken(dir / "missing.csv", dir / "broken.png", {}, kScript);
  const PlotOutcome failed = broken.finish(true);
  CHECK_FALSE(failed.written);
  CHECK(failed.message.find("failed to draw") != std::string::npos);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  CHECK(files == 3);  // table.csv, plot.png and started.png
}

TEST_CASE("Without its script the deployment plot says so") {
  const ScratchDirectory scratch("deployment-plot-script");
  const fs::path& dir = scratch.path();
  DeploymentPlotter plotter(dir / "table.csv", dir / "plot.png", {}, dir / "absent.py");
  const PlotOutcome outcome = plotter.finish(true);
  CHECK_FALSE(outcome.written);
  CHECK(outcome.message.find("plot_deployment.py was not found") != std::string::npos);
}

}  // namespace xshell::test
