// xshell: static equilibria of elastic rod scissor linkages.
#include <CLI/CLI.hpp>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"xshell: static equilibria of elastic rod scissor linkages"};
  app.set_version_flag("--version", XSHELL_VERSION);
  app.require_subcommand(1);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
