#include "design_command.hpp"

#include <cstdio>
#include <iostream>

#include "design_run.hpp"

namespace xshell {

int run_design_command(const DesignArguments& args, const std::atomic<bool>& stop) {
  DesignRequest request;
  request.config = args.config;
  request.out = args.out;
  request.init = args.init;
  DesignHooks hooks;
  hooks.stop = &stop;
  hooks.log = args.quiet ? nullptr : &std::cerr;
  const DesignOutcome outcome = run_design(request, hooks);
  if (!outcome.error.empty()) std::cerr << "xshell: error: " << outcome.error << "\n";
  if (outcome.report) {
    const nlohmann::json& r = *outcome.report;
    std::fprintf(stderr,
                 "xshell: design %s after %d iterations (%d evaluations): %s; fit max %.3e, "
                 "rms %.3e; outputs in %s\n",
                 r["status"].get<std::string>().c_str(), r["iterations"].get<int>(),
                 r["evaluations"].get<int>(), r["reason"].get<std::string>().c_str(),
                 r["fit"]["max"].get<double>(), r["fit"]["rms"].get<double>(),
                 outcome.directory.c_str());
  }
  return outcome.exit_status;
}

}  // namespace xshell
