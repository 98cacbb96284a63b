#include "command_line.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "exit_status.hpp"
#include "io/input_error.hpp"

namespace xshell {

namespace {

// A usage error in the documented form: one line "xshell: error: ...",
// pointing to the help of the command (`command` empty: of the program).
CommandLine usage_error(const std::string& what, const std::string& command) {
  std::string line = what;
  for (char& c : line)  // CLI11 may say it in several lines
    if (c == '\n') c = ' ';
  while (!line.empty() && line.back() == ' ') line.pop_back();
  CommandLine result;
  result.exit_status = kExitInvalidInput;
  result.error = "xshell: error: " + (command.empty() ? "" : command + ": ") +
                 printable(line, 2 * kMaxQuotedChars) + " (see xshell " +
                 (command.empty() ? "" : command + " ") + "--help)\n";
  return result;
}

// File and folder names may not be empty (before, `--out ""` ended in an
// internal error): a usage error, like the configuration's empty names.
const CLI::Validator kNonEmptyPath(
    [](std::string& value) {
      return value.empty() ? std::string("must name a file or folder, got an empty string")
                           : std::string();
    },
    "PATH", "non-empty path");

// CLI::Range lets NaN through (every comparison with it is false): `--grace
// nan` was accepted and acted as 0. Checked before the range.
const CLI::Validator kFiniteNumber(
    [](std::string& value) {
      char* end = nullptr;
      const double number = std::strtod(value.c_str(), &end);
      return end != value.c_str() && !std::isfinite(number)
                 ? "must be a finite number, got '" + value + "'"
                 : std::string();
    },
    "FINITE", "finite number");

// The subcommands' options, filled into `line`.
struct Subcommands {
  CLI::App* relax = nullptr;
  CLI::App* render = nullptr;
  CLI::App* fabricate = nullptr;
  CLI::App* design = nullptr;
};

CLI::App* add_design(CLI::App& app, DesignArguments& design) {
  CLI::App* c = app.add_subcommand(
      "design", "Find rest lengths whose deployed shell fits a target (the \"design\" section)");
  c->add_option("config", design.config, "Configuration (JSON) with a \"design\" section")
      ->required()
      ->check(kNonEmptyPath);
  c->add_option("--out", design.out, "Output directory (overrides output.directory)")
      ->check(kNonEmptyPath);
  c->add_option("--init", design.init, "Start from a state.json of the flat linkage")
      ->check(kNonEmptyPath);
  c->add_flag("--quiet", design.quiet, "No progress lines");
  return c;
}

CLI::App* add_relax(CLI::App& app, RelaxArguments& relax) {
  CLI::App* c = app.add_subcommand("relax", "Find the static equilibrium of a linkage");
  c->add_option("config", relax.config, "Configuration (JSON)")->required()->check(kNonEmptyPath);
  c->add_option("--solver", relax.solver,
                "newton | dynamics | kinetic-damping (overrides solver.method)");
  c->add_option("--out", relax.out, "Output directory (overrides output.directory)")
      ->check(kNonEmptyPath);
  c->add_option("--init", relax.init, "Start from a state.json written by an earlier run")
      ->check(kNonEmptyPath);
  c->add_option("--grace", relax.grace,
                "Seconds an iteration may go on after SIGINT/SIGTERM (default 10)")
      ->check(kFiniteNumber)
      ->check(CLI::Range(0.0, 86400.0));
  CLI::Option* quiet = c->add_flag("--quiet", relax.quiet, "No progress lines");
  CLI::Option* verbose =
      c->add_flag("--verbose", relax.verbose, "Progress lines even when stderr is not a terminal");
  c->add_option("--progress", relax.progress,
                "auto (default: text on a terminal, else plain) | text (a line per "
                "iteration) | plain (phases, a line every 5 s at most) | json (an object "
                "per line) | off")
      ->check(CLI::IsMember({"auto", "text", "plain", "json", "off"}))
      ->excludes(quiet)
      ->excludes(verbose);
  return c;
}

CLI::App* add_render(CLI::App& app, RenderArguments& render) {
  CLI::App* c = app.add_subcommand("render", "Render a run's final state (or .vtp files) to a PNG");
  c->add_option("inputs", render.inputs, "An output directory of `relax`, or .vtp files")
      ->required();
  c->add_option("--out", render.png, "PNG file to write")->required()->check(kNonEmptyPath);
  c->add_option("--width", render.width, "Picture width in pixels");
  c->add_option("--height", render.height, "Picture height in pixels");
  c->add_option_function<std::string>(
      "--color",
      [&render](const std::string& name) {
        render.color = name;
        render.color_given = true;
      },
      "Point or cell array to colour by (default bending_density where there is one; \"\" for "
      "none)");
  c->add_option("--view", render.view, "iso | top | front | side (default iso)")
      ->check(CLI::IsMember({"iso", "top", "front", "side"}));
  c->add_option_function<double>(
       "--scale-deflection", [&render](const double& k) { render.scale_deflection = k; },
       "Draw the displacement from the run's first step K times (K >= 0)")
      ->check(kFiniteNumber)
      ->check(CLI::NonNegativeNumber);
  return c;
}

CLI::App* add_fabricate(CLI::App& app, FabricateArguments& fabricate) {
  CLI::App* c = app.add_subcommand(
      "fabricate", "Write the fabrication data (cut lengths, drill stations) without solving");
  c->add_option("config", fabricate.config, "Configuration (JSON)")
      ->required()
      ->check(kNonEmptyPath);
  c->add_option("--init", fabricate.init,
                "Take the state from a state.json written by an earlier run")
      ->check(kNonEmptyPath);
  c->add_option("--out", fabricate.out, "Output directory (overrides output.directory)")
      ->check(kNonEmptyPath);
  return c;
}

Subcommands add_subcommands(CLI::App& app, CommandLine& line) {
  Subcommands s;
  s.relax = add_relax(app, line.relax);
  s.render = add_render(app, line.render);
  s.fabricate = add_fabricate(app, line.fabricate);
  s.design = add_design(app, line.design);
  return s;
}

}  // namespace

CommandLine parse_command_line(int argc, const char* const* argv) {
  // The command first: CLI11 would only say that one is required.
  const std::string commands = "the commands are relax, render, fabricate and design";
  if (argc < 2) return usage_error("no command given; " + commands, "");
  const std::string first = argv[1];
  if (first.empty() || (first[0] != '-' && first != "relax" && first != "render" &&
                        first != "fabricate" && first != "design"))
    return usage_error("unknown command '" + first + "'; " + commands, "");
  if (first[0] == '-' && first != "-h" && first != "--help" && first != "--version")
    return usage_error("unknown option '" + first + "' before the command; " + commands, "");

  CommandLine line;
  CLI::App app{"xshell: static equilibria of elastic rod scissor linkages"};
  app.set_version_flag("--version", XSHELL_VERSION);
  app.require_subcommand(1);
  const Subcommands s = add_subcommands(app, line);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --version
      std::ostringstream out, err;
      line.exit_status = app.exit(e, out, err);
      line.output = out.str();
      line.error = err.str();
      return line;
    }
    const std::string command = s.relax->parsed()       ? "relax"
                                : s.render->parsed()    ? "render"
                                : s.fabricate->parsed() ? "fabricate"
                                : s.design->parsed()    ? "design"
                                                        : "";
    return usage_error(e.what(), command);
  }
  line.command = *s.relax       ? Command::Relax
                 : *s.fabricate ? Command::Fabricate
                 : *s.design    ? Command::Design
                                : Command::Render;
  return line;
}

}  // namespace xshell
