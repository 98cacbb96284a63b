// The stability analysis' time budget (stability_analysis.hpp): a point in
// time after which its iterative parts (Lanczos, the unloaded Newton solve)
// stop. Spectra's eigensolvers have no callback: their operators check the
// deadline at every product or solve and throw DeadlinePassed, which the
// analysis catches and reports as the status "time_limit".
#pragma once

#include <chrono>
#include <optional>
#include <stdexcept>

namespace xshell {

using AnalysisClock = std::chrono::steady_clock;

struct AnalysisDeadline {
  std::optional<AnalysisClock::time_point> at;  // none: no limit
  bool passed() const { return at && AnalysisClock::now() >= *at; }
  // Throws DeadlinePassed when passed().
  void check() const;
};

struct DeadlinePassed : std::runtime_error {
  DeadlinePassed() : std::runtime_error("the analysis' time budget ran out") {}
};

inline void AnalysisDeadline::check() const {
  if (passed()) throw DeadlinePassed();
}

// The status of an analysis part stopped by its deadline.
constexpr const char* kTimeLimit = "time_limit";

}  // namespace xshell
