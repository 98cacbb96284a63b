// Fuzzes the command line: the input, split on NUL and newline, is the
// argument vector after the program's name, parsed as main() parses it
// (app/command_line.hpp). The command it chooses is not run (its readers
// have fuzzers of their own). Any input either chooses a command with
// usable arguments or ends the process with exit 0 (help, version) or 2
// and one "xshell: error: ..." line; anything else aborts (a finding).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "app/command_line.hpp"
#include "app/exit_status.hpp"

namespace {

void require(bool condition) {
  if (!condition) std::abort();
}

bool one_error_line(const std::string& error) {
  return error.rfind("xshell: error: ", 0) == 0 && error.back() == '\n' &&
         error.find('\n') == error.size() - 1;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> args{"xshell"};
  std::string arg;
  for (size_t i = 0; i < size; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\0' || c == '\n') {
      args.push_back(arg);
      arg.clear();
    } else {
      arg += c;
    }
  }
  if (size > 0) args.push_back(arg);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());

  const xshell::CommandLine line =
      xshell::parse_command_line(static_cast<int>(argv.size()), argv.data());
  switch (line.command) {
    case xshell::Command::None:
      if (line.exit_status == 0) {
        require(!line.output.empty() && line.error.empty());
      } else {
        require(line.exit_status == xshell::kExitInvalidInput);
        require(line.output.empty() && one_error_line(line.error));
      }
      break;
    case xshell::Command::Relax:
      require(!line.relax.config.empty() && (!line.relax.out || !line.relax.out->empty()) &&
              (!line.relax.init || !line.relax.init->empty()));
      require(std::isfinite(line.relax.grace) && line.relax.grace >= 0.0 &&
              line.relax.grace <= 86400.0);
      break;
    case xshell::Command::Render:
      require(!line.render.inputs.empty() && !line.render.png.empty());
      break;
    case xshell::Command::Fabricate:
      require(!line.fabricate.config.empty() &&
              (!line.fabricate.out || !line.fabricate.out->empty()));
      break;
    case xshell::Command::Design:
      require(!line.design.config.empty() && (!line.design.out || !line.design.out->empty()) &&
              (!line.design.init || !line.design.init->empty()));
      break;
  }
  return 0;
}
