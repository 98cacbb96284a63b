#include "relax_command.hpp"

#include <cstdio>
#include <iostream>

#include "relax_run.hpp"

namespace xshell {

namespace {

// The last line of a run that wrote its outputs.
void print_outcome(const RunSummary& summary, const std::string& directory) {
  std::fprintf(stderr,
               "xshell: %s after %ld %s: %s; energy %.10e, gradient %.3e (tolerance %.1e), %s; "
               "outputs in %s\n",
               summary.status.c_str(), summary.iterations,
               summary.solver == "dynamics" ? "steps" : "iterations", summary.reason.c_str(),
               summary.energy.total(), summary.gradient_norm, summary.gradient_tolerance,
               !summary.stable   ? "stability not checked (not converged)"
               : *summary.stable ? "stable"
                                 : "NOT stable (a saddle or a mechanism)",
               directory.c_str());
}

}  // namespace

int run_relax(const RelaxArguments& args, const std::atomic<bool>& stop) {
  RelaxRequest request;
  request.config = args.config;
  request.solver = args.solver;
  request.out = args.out;
  request.init = args.init;
  request.grace = args.grace;
  RelaxHooks hooks;
  hooks.stop = &stop;
  hooks.log = &std::cerr;
  hooks.progress = args.quiet ? Toggle::Off : args.verbose ? Toggle::On : Toggle::Auto;
  // --quiet and --verbose exclude --progress (command_line.cpp).
  if (!args.quiet && !args.verbose) hooks.progress_style = parse_progress_style(args.progress);
  const RelaxOutcome outcome = relax(request, hooks);
  if (!outcome.error.empty())
    std::cerr << "xshell: error: " << outcome.error << "\n";
  else if (outcome.summary)
    print_outcome(*outcome.summary, outcome.directory);
  return outcome.exit_status;
}

}  // namespace xshell
