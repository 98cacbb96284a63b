#include "run_progress.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "io/optional_json.hpp"

namespace xshell {

namespace {

std::string fixed(double x, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, x);
  return text;
}

std::string scientific(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6e", x);
  return text;
}

// A sample as a plain line: "xshell: analysis unloaded_equilibrium: iteration 3, energy ...".
std::string sample_text(const ProgressSample& s, double elapsed) {
  std::string text = "xshell: " + s.phase + (s.stage.empty() ? "" : " " + s.stage) + ": ";
  if (s.step) text += "step " + std::to_string(*s.step) + ", ";
  if (s.angle) text += "angle " + fixed(*s.angle, 6) + " rad, ";
  text += "iteration " + std::to_string(s.iteration);
  if (s.energy) text += ", energy " + scientific(*s.energy);
  if (s.gradient) text += ", gradient " + scientific(*s.gradient);
  return text + ", " + fixed(elapsed, 1) + " s";
}

}  // namespace

double RunProgress::elapsed() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void RunProgress::line(const std::string& text) {
  std::fputs((text + "\n").c_str(), out_);
  std::fflush(out_);
}

void RunProgress::phase(const std::string& name, const std::string& stage) {
  if (style_ == ProgressStyle::Off) return;
  if (style_ == ProgressStyle::Json) {
    line(nlohmann::json(
             {{"event", "phase"}, {"phase", name}, {"stage", stage}, {"elapsed", elapsed()}})
             .dump());
    return;
  }
  line("xshell: " + name + (stage.empty() ? "" : " " + stage) + " (" + fixed(elapsed(), 1) + " s)");
}

void RunProgress::sample(const ProgressSample& s, bool own_line) {
  const double now = elapsed();
  switch (style_) {
    case ProgressStyle::Off:
      return;
    case ProgressStyle::Text:
      if (own_line) line(sample_text(s, now));
      return;
    case ProgressStyle::Plain:
      if (now - last_plain_ < kPlainInterval) return;
      last_plain_ = now;
      line(sample_text(s, now));
      return;
    case ProgressStyle::Json:
      nlohmann::json j = {{"event", "iteration"},
                          {"phase", s.phase},
                          {"stage", s.stage},
                          {"iteration", s.iteration},
                          {"energy", optional_json(s.energy)},
                          {"gradient", optional_json(s.gradient)},
                          {"elapsed", now}};
      if (s.step) j["step"] = *s.step;
      if (s.angle) j["angle"] = *s.angle;
      line(j.dump());
      return;
  }
}

void RunProgress::finish(const std::string& status, const RunTimings& t, double wall_seconds) {
  if (style_ == ProgressStyle::Off) return;
  if (style_ == ProgressStyle::Json) {
    line(nlohmann::json({{"event", "done"},
                         {"phase", "done"},
                         {"status", status},
                         {"elapsed", wall_seconds},
                         {"timings",
                          {{"load", t.load},
                           {"setup", t.setup},
                           {"solve", t.solve},
                           {"analysis", t.analysis},
                           {"output", t.output}}}})
             .dump());
    return;
  }
  line("xshell: times: load " + fixed(t.load, 2) + " s, setup " + fixed(t.setup, 2) + " s, solve " +
       fixed(t.solve, 2) + " s, analysis " + fixed(t.analysis, 2) + " s, output " +
       fixed(t.output, 2) + " s (wall " + fixed(wall_seconds, 2) + " s)");
}

ProgressStyle resolve_progress(std::optional<ProgressStyle> asked, Toggle configured,
                               bool terminal) {
  if (asked) return *asked;
  if (configured == Toggle::On) return ProgressStyle::Text;
  if (configured == Toggle::Off) return ProgressStyle::Off;
  return terminal ? ProgressStyle::Text : ProgressStyle::Plain;
}

std::optional<ProgressStyle> parse_progress_style(const std::string& name) {
  if (name == "auto") return std::nullopt;
  if (name == "text") return ProgressStyle::Text;
  if (name == "plain") return ProgressStyle::Plain;
  if (name == "json") return ProgressStyle::Json;
  if (name == "off") return ProgressStyle::Off;
  throw std::invalid_argument("unknown progress style '" + name +
                              "' (choose auto, text, plain, json or off)");
}

}  // namespace xshell
