// xshell: static equilibria of elastic rod scissor linkages.
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <iostream>
#include <new>
#include <string>

#include "exit_status.hpp"
#include "fabricate_command.hpp"
#include "io/input_error.hpp"
#include "relax_command.hpp"
#include "render_command.hpp"

namespace {
std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

// A usage error in the documented form: one line "xshell: error: ...",
// pointing to the help of the command (`command` empty: of the program).
int usage_error(const std::string& what, const std::string& command) {
  std::string line = what;
  for (char& c : line)  // CLI11 may say it in several lines
    if (c == '\n') c = ' ';
  while (!line.empty() && line.back() == ' ') line.pop_back();
  std::cerr << "xshell: error: " << (command.empty() ? "" : command + ": ")
            << xshell::printable(line, 2 * xshell::kMaxQuotedChars) << " (see xshell "
            << (command.empty() ? "" : command + " ") << "--help)\n";
  return xshell::kExitInvalidInput;
}

// File and folder names may not be empty (before, `--out ""` ended in an
// internal error): a usage error, like the configuration's empty names.
const CLI::Validator kNonEmptyPath(
    [](std::string& value) {
      return value.empty() ? std::string("must name a file or folder, got an empty string")
                           : std::string();
    },
    "PATH", "non-empty path");
}  // namespace

int main(int argc, char** argv) {
  using namespace xshell;
  CLI::App app{"xshell: static equilibria of elastic rod scissor linkages"};
  app.set_version_flag("--version", XSHELL_VERSION);
  app.require_subcommand(1);

  RelaxArguments relax;
  CLI::App* relax_cmd = app.add_subcommand("relax", "Find the static equilibrium of a linkage");
  relax_cmd->add_option("config", relax.config, "Configuration (JSON)")
      ->required()
      ->check(kNonEmptyPath);
  relax_cmd->add_option("--solver", relax.solver,
                        "newton | dynamics | kinetic-damping (overrides solver.method)");
  relax_cmd->add_option("--out", relax.out, "Output directory (overrides output.directory)")
      ->check(kNonEmptyPath);
  relax_cmd->add_option("--init", relax.init, "Start from a state.json written by an earlier run")
      ->check(kNonEmptyPath);
  relax_cmd
      ->add_option("--grace", relax.grace,
                   "Seconds an iteration may go on after SIGINT/SIGTERM (default 10)")
      ->check(CLI::Range(0.0, 86400.0));
  relax_cmd->add_flag("--quiet", relax.quiet, "No progress lines");
  relax_cmd->add_flag("--verbose", relax.verbose,
                      "Progress lines even when stderr is not a terminal");

  RenderArguments render;
  CLI::App* render_cmd =
      app.add_subcommand("render", "Render a run's final state (or .vtp files) to a PNG");
  render_cmd->add_option("inputs", render.inputs, "An output directory of `relax`, or .vtp files")
      ->required();
  render_cmd->add_option("--out", render.png, "PNG file to write")
      ->required()
      ->check(kNonEmptyPath);
  render_cmd->add_option("--width", render.width, "Picture width in pixels");
  render_cmd->add_option("--height", render.height, "Picture height in pixels");
  render_cmd->add_option("--color", render.color, "Point or cell array to colour by");

  FabricateArguments fabricate;
  CLI::App* fabricate_cmd = app.add_subcommand(
      "fabricate", "Write the fabrication data (cut lengths, drill stations) without solving");
  fabricate_cmd->add_option("config", fabricate.config, "Configuration (JSON)")
      ->required()
      ->check(kNonEmptyPath);
  fabricate_cmd
      ->add_option("--init", fabricate.init,
                   "Take the state from a state.json written by an earlier run")
      ->check(kNonEmptyPath);
  fabricate_cmd->add_option("--out", fabricate.out, "Output directory (overrides output.directory)")
      ->check(kNonEmptyPath);

  // The command first: CLI11 would only say that one is required.
  const std::string commands = "the commands are relax, render and fabricate";
  if (argc < 2) return usage_error("no command given; " + commands, "");
  const std::string first = argv[1];
  if (first.empty() ||
      (first[0] != '-' && first != "relax" && first != "render" && first != "fabricate"))
    return usage_error("unknown command '" + first + "'; " + commands, "");
  if (first[0] == '-' && first != "-h" && first != "--help" && first != "--version")
    return usage_error("unknown option '" + first + "' before the command; " + commands, "");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    const std::string command = relax_cmd->parsed()       ? "relax"
                                : render_cmd->parsed()    ? "render"
                                : fabricate_cmd->parsed() ? "fabricate"
                                                          : "";
    return usage_error(e.what(), command);
  }
  // The commands report every foreseen failure themselves; this is the last
  // net, so that nothing ends in std::terminate (an abort and a core dump).
  try {
    if (*relax_cmd) {
      // A relax run stops at the next iteration and writes its last state and
      // summary; any other command keeps the default (immediate) handling.
      std::signal(SIGINT, on_signal);
      std::signal(SIGTERM, on_signal);
      // A closed stderr (`xshell relax ... 2>&1 | head`) must not kill the
      // run before it writes its outputs: a failed write is harmless.
      std::signal(SIGPIPE, SIG_IGN);
      return run_relax(relax, g_stop);
    }
    if (*fabricate_cmd) return run_fabricate(fabricate);
    return run_render(render);
  } catch (const std::bad_alloc&) {
    std::cerr
        << "xshell: error: out of memory (a linkage or subdivisions too large for this machine?)\n";
  } catch (const std::exception& e) {
    std::cerr << "xshell: error: internal error: " << e.what() << "\n";
  }
  return kExitInternalError;
}
