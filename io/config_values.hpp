// Checked values of the configuration files (config.hpp, design_config.hpp):
// each reads one JsonField and throws its InputError ("FILE: PATH: what")
// when the value is out of range.
#pragma once

#include <string>

#include "config.hpp"
#include "json_field.hpp"

namespace xshell {

double positive(const JsonField& f);
double non_negative(const JsonField& f);
// In the open interval (lo, hi), spelled `interval` in messages.
double inside(const JsonField& f, double lo, double hi, const std::string& interval);
double angle(const JsonField& f);  // in (0, pi) radians
int at_least(const JsonField& f, int lo);
int vertex_index(const JsonField& f);  // >= 0
Toggle toggle(const JsonField& f);     // true, false or "auto"

// `text`, a path relative to `base_dir` (the configuration's folder),
// resolved (left as it is when base_dir is empty or the path absolute).
std::string resolve(const std::string& text, const std::string& base_dir);
// A file's name: a non-empty string without NUL bytes, resolved.
std::string file_path(const JsonField& f, const std::string& base_dir);

}  // namespace xshell
