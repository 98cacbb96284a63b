// Runs the xshell program for the command tests and captures what it says.
#pragma once

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "scratch_directory.hpp"

namespace xshell::test {

namespace fs = std::filesystem;

struct CommandResult {
  int status = -1;     // exit status
  std::string errors;  // stderr
};

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline nlohmann::json read_json(const fs::path& path) {
  return nlohmann::json::parse(read_text(path));
}

inline void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Runs `PROGRAM ARGS` (arguments already quoted as needed) in `dir`.
inline CommandResult run_program(const fs::path& program, const std::string& args,
                                 const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string command = "cd '" + dir.string() + "' && '" + program.string() + "' " + args +
                              " > /dev/null 2> '" + err.string() + "'";
  const int raw = std::system(command.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.errors = read_text(err);
  return r;
}

// Runs `xshell ARGS` (arguments already quoted as needed) in `dir`.
inline CommandResult run_xshell(const std::string& args, const fs::path& dir) {
  return run_program(XSHELL_BINARY, args, dir);
}

// A configuration of the bundled grid sample under gravity, writing to `out`.
inline std::string sample_config(const fs::path& out, const std::string& extra = "",
                                 const std::string& linkage = "grid.obj") {
  return R"({
  "linkage": ")" +
         (fs::path(XSHELL_SAMPLES_DIR) / linkage).string() + R"(",
  "subdivisions": 6,
  "rest_shape": "straight",
  "material": {"young_modulus": 2.0e10, "density": 1800,
               "cross_section": {"shape": "rectangle", "width": 0.01, "height": 0.007}},
  "supports": [{"vertex": 1, "fix": ["position"]}, {"vertex": 4, "fix": ["position"]},
               {"vertex": 9, "fix": ["position"]}, {"vertex": 28, "fix": ["position"]}],
  "loads": {"gravity": [0, 0, -9.81], "forces": [{"vertex": 13, "force": [0, 0, -5.0]}]},
  "output": {"directory": ")" +
         out.string() + R"("})" + extra + R"(
})";
}

}  // namespace xshell::test
