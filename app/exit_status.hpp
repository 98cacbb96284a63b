// Exit statuses of the xshell command (documented in the README).
#pragma once

namespace xshell {

enum ExitStatus : int {
  kExitConverged = 0,      // converged (stable or not: see summary.json)
  kExitInternalError = 1,  // an unforeseen error (out of memory, a bug): one line says what
  kExitInvalidInput = 2,   // usage, configuration, linkage or state rejected
  kExitNotConverged = 3,   // the solve did not converge; the last state is written
  kExitOutputFailed = 4,   // an output could not be written
  kExitInterrupted = 130   // SIGINT or SIGTERM; the last state is written
};

}  // namespace xshell
