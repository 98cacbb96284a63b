// The command line of xshell: its parsing and the choice of the command to
// run, without running it or leaving the process, so that main() and the
// command-line fuzzer (fuzz/fuzz_command_line.cpp) go through the same code.
#pragma once

#include <string>

#include "design_command.hpp"
#include "fabricate_command.hpp"
#include "relax_command.hpp"
#include "render_command.hpp"

namespace xshell {

enum class Command { None, Relax, Render, Fabricate, Design };

struct CommandLine {
  // The command to run with its arguments below; None: nothing to run, the
  // process ends with exit_status after printing `output` to stdout (--help,
  // --version) and `error` to stderr (a usage error: one line, "xshell:
  // error: ...").
  Command command = Command::None;
  RelaxArguments relax;
  RenderArguments render;
  FabricateArguments fabricate;
  DesignArguments design;
  int exit_status = 0;
  std::string output;
  std::string error;
};

// Parses argv[0 .. argc) (argv[0]: the program's name). Throws nothing but
// std::bad_alloc.
CommandLine parse_command_line(int argc, const char* const* argv);

}  // namespace xshell
