// The wall clock of the solvers' progress reports.
#pragma once

#include <chrono>

namespace xshell {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace xshell
