#include "json_field.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <set>

#include "input_error.hpp"

namespace xshell {
namespace {

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

std::string quoted_list(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + quoted(item);
  return out;
}

// "LINE:COLUMN" (both 1-based) of the character at 1-based byte `byte`, the
// position nlohmann's parse_error reports.
std::string line_and_column(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
  const std::size_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
  const std::size_t line_start = text.rfind('\n', end == 0 ? std::string::npos : end - 1);
  const std::size_t column = line_start == std::string::npos ? end + 1 : end - line_start;
  return std::to_string(line) + ":" + std::to_string(column);
}

// nlohmann's message without its "[json.exception...] parse error at ...: "
// prefix, whose position we give ourselves.
std::string parse_error_reason(const std::string& what) {
  const std::size_t at = what.find("parse error");
  const std::size_t colon = what.find(": ", at == std::string::npos ? 0 : at);
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

// "; JSON has no NaN or Infinity..." when the word at 1-based byte `byte`
// (where the parser stopped) spells one of them, else "".
std::string non_finite_hint(const std::string& text, std::size_t byte) {
  auto is_letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
  std::size_t begin = std::min(byte > 0 ? byte - 1 : 0, text.size());
  while (begin > 0 && is_letter(text[begin - 1])) --begin;
  std::size_t end = begin;
  while (end < text.size() && is_letter(text[end])) ++end;
  std::string word = text.substr(begin, end - begin);
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (word != "nan" && word != "inf" && word != "infinity") return "";
  return "; JSON has no NaN or Infinity: every number must be finite";
}

// Follows the parser's events to know the JSON path of each value, to report
// a key given twice in one object (nlohmann would keep the last silently) and
// a number that overflows to infinity.
class PathTracker {
 public:
  explicit PathTracker(const std::string& file) : file_(file) {}

  bool on_event(nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        open_.push_back({event == Event::array_start, next_path(), 0, "", {}});
        break;
      case Event::object_end:
      case Event::array_end:
        open_.pop_back();
        break;
      case Event::key: {
        Open& object = open_.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second)
          throw InputError(file_ + ": " + join(object.path, object.key) +
                           ": key given twice in the same object");
        break;
      }
      case Event::value: {
        const std::string path = next_path();
        if (parsed.is_number_float() && !std::isfinite(parsed.get<double>()))
          throw InputError(prefix(path) + "number out of range (it overflows to infinity)");
        break;
      }
    }
    return true;
  }

  // The path of the value being read.
  std::string pending_path() const {
    if (open_.empty()) return "";
    const Open& parent = open_.back();
    if (parent.array) return parent.path + "[" + std::to_string(parent.count) + "]";
    return join(parent.path, parent.key);
  }

  // "FILE: PATH: " ("FILE: " for the document).
  std::string prefix(const std::string& path) const {
    return file_ + ": " + (path.empty() ? "" : path + ": ");
  }

 private:
  struct Open {
    bool array;
    std::string path;
    int count;                   // elements so far (arrays)
    std::string key;             // the key being read (objects)
    std::set<std::string> keys;  // keys so far (objects)
  };

  // The path of the value that starts now; counts it in its array.
  std::string next_path() {
    std::string path = pending_path();
    if (!open_.empty() && open_.back().array) ++open_.back().count;
    return path;
  }

  const std::string& file_;
  std::vector<Open> open_;
};

}  // namespace

nlohmann::json parse_json(const std::string& text, const std::string& file) {
  PathTracker tracker(file);
  try {
    return nlohmann::json::parse(
        text, [&tracker](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
          return tracker.on_event(event, parsed);
        });
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file + ":" + line_and_column(text, e.byte) + ": invalid JSON: " +
                     parse_error_reason(e.what()) + non_finite_hint(text, e.byte));
  } catch (const nlohmann::json::out_of_range& e) {
    // 406: a number literal beyond the range of double ("1e999"), reported
    // before the value reaches the tracker.
    if (e.id != 406) throw;
    const std::string what = e.what();
    const std::size_t open = what.find('\''), close = what.rfind('\'');
    const std::string literal = open < close && close != std::string::npos
                                    ? " " + what.substr(open + 1, close - open - 1)
                                    : "";
    throw InputError(tracker.prefix(tracker.pending_path()) + "number" + literal +
                     " out of range (it overflows to infinity)");
  }
}

int edit_distance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];  // distance(a[0, i-1), b[0, j-1))
    row[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const int substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({substitute, row[j] + 1, row[j - 1] + 1});
    }
  }
  return row[b.size()];
}

JsonField::JsonField(const nlohmann::json& value, std::string path, std::string file)
    : value_(&value), path_(std::move(path)), file_(std::move(file)) {}

void JsonField::fail(const std::string& what) const {
  throw InputError(file_ + ": " + (path_.empty() ? "" : path_ + ": ") + what);
}

std::string JsonField::describe() const {
  const nlohmann::json& v = *value_;
  switch (v.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "an array of " + std::to_string(v.size()) + " element(s)";
    case nlohmann::json::value_t::string: {
      const std::string s = v.get<std::string>();
      return "a string (" + quoted(s.size() > 40 ? s.substr(0, 40) + "..." : s) + ")";
    }
    case nlohmann::json::value_t::boolean:
      return std::string("a boolean (") + (v.get<bool>() ? "true" : "false") + ")";
    default:
      return "a number (" + v.dump() + ")";
  }
}

void JsonField::check_keys(const std::vector<std::string>& valid) const {
  if (!value_->is_object()) fail("expected an object, got " + describe());
  for (const auto& item : value_->items()) {
    const std::string& key = item.key();
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    const auto closest = std::min_element(valid.begin(), valid.end(), [&](auto& a, auto& b) {
      return edit_distance(key, a) < edit_distance(key, b);
    });
    const std::string where = path_.empty() ? "at the top level" : "in " + path_;
    std::string message = file_ + ": unknown key " + quoted(key) + " " + where;
    const int close_enough = std::max(2, static_cast<int>(key.size()) / 3);
    if (closest != valid.end() && edit_distance(key, *closest) <= close_enough)
      message += "; did you mean " + quoted(*closest) + "?";
    else
      message += "; valid keys are " + quoted_list(valid);
    throw InputError(message);
  }
}

std::optional<JsonField> JsonField::find(const std::string& key) const {
  if (!value_->is_object()) fail("expected an object, got " + describe());
  const auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return JsonField(*it, join(path_, key), file_);
}

JsonField JsonField::require(const std::string& key) const {
  if (auto field = find(key)) return *field;
  throw InputError(file_ + ": missing required key " + quoted(join(path_, key)));
}

std::vector<JsonField> JsonField::elements() const {
  if (!value_->is_array()) fail("expected an array, got " + describe());
  std::vector<JsonField> out;
  for (std::size_t i = 0; i < value_->size(); ++i)
    out.emplace_back((*value_)[i], path_ + "[" + std::to_string(i) + "]", file_);
  return out;
}

double JsonField::number() const {
  if (!value_->is_number()) fail("expected a number, got " + describe());
  const double x = value_->get<double>();
  if (!std::isfinite(x)) fail("is not a finite number");
  return x;
}

int JsonField::integer() const {
  if (!value_->is_number()) fail("expected an integer, got " + describe());
  const double x = number();
  if (x != std::trunc(x)) fail("expected an integer, got " + describe());
  if (x < INT_MIN || x > INT_MAX) fail("integer " + value_->dump() + " is out of range");
  return static_cast<int>(x);
}

bool JsonField::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false, got " + describe());
  return value_->get<bool>();
}

std::string JsonField::string() const {
  if (!value_->is_string()) fail("expected a string, got " + describe());
  return value_->get<std::string>();
}

Eigen::Vector3d JsonField::vector3() const {
  if (!value_->is_array() || value_->size() != 3)
    fail("expected an array of three numbers [x, y, z], got " + describe());
  const auto items = elements();
  return {items[0].number(), items[1].number(), items[2].number()};
}

void JsonField::fail_choice(const std::string& given, const std::vector<std::string>& valid) const {
  fail(quoted(given) + " is not a valid choice; expected one of " + quoted_list(valid));
}

}  // namespace xshell
