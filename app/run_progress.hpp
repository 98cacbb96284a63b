// What a run of `xshell relax` says on stderr as it goes (README,
// "Progress"), in one of four styles:
//   Text   every solver iteration (or deployment step) as a line, as on a
//          terminal (`--progress text`, `--verbose`);
//   Plain  for a log, a notebook or CI (auto without a terminal): the start
//          of every phase and at most one line every kPlainInterval seconds;
//   Json   one JSON object per line, for programs (`--progress json`): every
//          iteration, every phase's start and a last object with the times;
//   Off    nothing (`--quiet`, `--progress off`).
// Every style but Off ends with a line giving each phase's time.
#pragma once

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include "io/config.hpp"
#include "io/summary_file.hpp"

namespace xshell {

enum class ProgressStyle { Off, Text, Plain, Json };

// Seconds between two of Plain's iteration lines, at least.
constexpr double kPlainInterval = 5.0;

// One iteration of a phase.
struct ProgressSample {
  std::string phase;  // "solve", "deploy", "analysis" (see phase())
  std::string stage;  // within the phase: the solver ("newton", ...) or the analysis' part
  long iteration = 0;
  std::optional<double> energy;
  std::optional<double> gradient;  // the dimensionless gradient measure
  std::optional<int> step;         // a deployment's step
  std::optional<double> angle;     // a deployment's average opening angle, radians
};

class RunProgress {
 public:
  using Clock = std::chrono::steady_clock;
  RunProgress(ProgressStyle style, Clock::time_point start, std::FILE* out = stderr)
      : style_(style), start_(start), out_(out) {}

  ProgressStyle style() const { return style_; }
  bool on() const { return style_ != ProgressStyle::Off; }
  // Whether the solvers print their own line for every iteration.
  bool every_iteration() const { return style_ == ProgressStyle::Text; }

  // A phase (or a stage of one, e.g. "analysis" "eigen_modes") starts.
  void phase(const std::string& name, const std::string& stage = "");
  // An iteration: Json prints it, Plain at most one every kPlainInterval
  // seconds, Text only when `own_line` (the solvers print their own).
  void sample(const ProgressSample& s, bool own_line = false);
  // The last line: the run's status and each phase's time.
  void finish(const std::string& status, const RunTimings& timings, double wall_seconds);

  double elapsed() const;

 private:
  void line(const std::string& text);

  ProgressStyle style_;
  Clock::time_point start_;
  std::FILE* out_;
  double last_plain_ = -1e300;  // elapsed() at Plain's last iteration line
};

// The style a run takes: `asked` by the command line (or the Python
// module), else the configuration's output.progress (on: Text, off: Off),
// else auto: Text when stderr is a terminal, Plain when not.
ProgressStyle resolve_progress(std::optional<ProgressStyle> asked, Toggle configured,
                               bool terminal);

// "auto" | "text" | "json" | "off" (or "plain") into a style (nullopt for auto);
// throws std::invalid_argument for any other name.
std::optional<ProgressStyle> parse_progress_style(const std::string& name);

}  // namespace xshell
