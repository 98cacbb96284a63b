#include "config_values.hpp"

#include <cmath>
#include <filesystem>

#include "input_error.hpp"

namespace xshell {

double positive(const JsonField& f) {
  const double x = f.number();
  if (!(x > 0)) f.fail("must be > 0, got " + f.value().dump());
  return x;
}

double non_negative(const JsonField& f) {
  const double x = f.number();
  if (!(x >= 0)) f.fail("must be >= 0, got " + f.value().dump());
  return x;
}

// In the open interval (lo, hi), spelled `interval` in messages.
double inside(const JsonField& f, double lo, double hi, const std::string& interval) {
  const double x = f.number();
  if (!(x > lo && x < hi)) f.fail("must be in " + interval + ", got " + f.value().dump());
  return x;
}

double angle(const JsonField& f) { return inside(f, 0, M_PI, "(0, pi) radians"); }

int at_least(const JsonField& f, int lo) {
  const int n = f.integer();
  if (n < lo) f.fail("must be >= " + std::to_string(lo) + ", got " + std::to_string(n));
  return n;
}

int vertex_index(const JsonField& f) {
  const int n = f.integer();
  if (n < 0) f.fail("a vertex index is 0-based and must be >= 0, got " + std::to_string(n));
  return n;
}

Toggle toggle(const JsonField& f) {
  if (f.is_boolean()) return f.boolean() ? Toggle::On : Toggle::Off;
  if (!f.is_string() || f.string() != "auto")
    f.fail("expected true, false or \"auto\", got " + f.describe());
  return Toggle::Auto;
}

// `text`, a path relative to `base_dir` (the configuration's folder), resolved.
std::string resolve(const std::string& text, const std::string& base_dir) {
  const std::filesystem::path path(text);
  if (base_dir.empty() || path.is_absolute()) return text;
  return (std::filesystem::path(base_dir) / path).lexically_normal().string();
}

std::string file_path(const JsonField& f, const std::string& base_dir) {
  const std::string text = f.string();
  if (text.empty()) f.fail("must name a file or folder, got an empty string");
  // The system would read the name only up to the NUL: another file.
  if (text.find('\0') != std::string::npos)
    f.fail("a file name cannot contain a NUL byte, got \"" + printable(text) + "\"");
  return resolve(text, base_dir);
}

}  // namespace xshell
