// xshell: static equilibria of elastic rod scissor linkages.
#include <atomic>
#include <csignal>
#include <iostream>
#include <new>
#include <string>

#include "command_line.hpp"
#include "exit_status.hpp"
#ifdef XSHELL_FORWARD_TO_FULL
#include "full_program.hpp"
#endif

namespace {
std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  using namespace xshell;
  // The commands report every foreseen failure themselves; this is the last
  // net, so that nothing ends in std::terminate (an abort and a core dump).
  try {
    const CommandLine line = parse_command_line(argc, argv);
    switch (line.command) {
      case Command::None:
        std::cout << line.output;
        std::cerr << line.error;
        return line.exit_status;
      case Command::Relax:
        // A relax run stops at the next iteration and writes its last state
        // and summary; any other command keeps the default (immediate)
        // handling.
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        // A closed stderr (`xshell relax ... 2>&1 | head`) must not kill the
        // run before it writes its outputs: a failed write is harmless.
        std::signal(SIGPIPE, SIG_IGN);
        return run_relax(line.relax, g_stop);
      case Command::Fabricate:
        return run_fabricate(line.fabricate);
#ifdef XSHELL_FORWARD_TO_FULL
      case Command::Render:
      case Command::Design:
        return run_in_full_program(argv);
#else
      case Command::Render:
        return run_render(line.render);
      case Command::Design:
        // Stops at the next design iteration and writes the best design so far.
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        std::signal(SIGPIPE, SIG_IGN);
        return run_design_command(line.design, g_stop);
#endif
    }
  } catch (const std::bad_alloc&) {
    std::cerr
        << "xshell: error: out of memory (a linkage or subdivisions too large for this machine?)\n";
  } catch (const std::exception& e) {
    std::cerr << "xshell: error: internal error: " << e.what() << "\n";
  }
  return kExitInternalError;
}
