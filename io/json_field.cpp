#include "json_field.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>

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
// position nlohmann's parser reports.
std::string line_and_column(const std::string& text, std::size_t byte) {
  const std::size_t at = std::min(byte > 0 ? byte - 1 : 0, text.size());  // 0-based
  const std::size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  const std::size_t line_start = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
  const std::size_t column = line_start == std::string::npos ? at + 1 : at - line_start;
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
// (where the parser stopped) spells one of them, "; JSON has no comments"
// when the parser stopped at a '/', else "".
std::string syntax_hint(const std::string& text, std::size_t byte, const std::string& token) {
  if (!token.empty() && token.back() == '/')
    return "; JSON has no comments (// or /* */): remove them";
  auto is_letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
  std::size_t begin = std::min(byte > 0 ? byte - 1 : 0, text.size());
  while (begin > 0 && is_letter(text[begin - 1])) --begin;
  std::size_t end = begin;
  while (end < text.size() && end - begin <= 8 && is_letter(text[end])) ++end;
  std::string word = text.substr(begin, end - begin);
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (word != "nan" && word != "inf" && word != "infinity") return "";
  return "; JSON has no NaN or Infinity: every number must be finite";
}

// Builds the document from the parser's events (nlohmann's SAX interface) in
// time linear in the text. (nlohmann's parse with a callback, used before,
// scans every array again at the end of each object in it: quadratic.) It
// refuses a key given twice in one object (nlohmann would keep the last
// silently), a number that overflows to infinity, and nesting deeper than
// kMaxJsonDepth. It knows where it is by a stack of the open arrays and
// objects, and spells a JSON path only for a message.
class DocumentBuilder {
 public:
  using json = nlohmann::json;
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  DocumentBuilder(json& root, const std::string& text, const std::string& file)
      : root_(root), text_(text), file_(file) {}

  bool null() { return add(nullptr); }
  bool boolean(bool value) { return add(value); }
  bool number_integer(number_integer_t value) { return add(value); }
  bool number_unsigned(number_unsigned_t value) { return add(value); }
  bool number_float(number_float_t value, const string_t& literal) {
    if (!std::isfinite(value)) overflow(literal);
    return add(value);
  }
  bool string(string_t& value) { return add(std::move(value)); }
  bool binary(binary_t& value) { return add(json::binary(std::move(value))); }

  bool start_object(std::size_t) { return open(json::value_t::object); }
  bool key(string_t& key) {
    Open& object = open_.back();
    object.key = key;
    auto& members = object.value->get_ref<json::object_t&>();
    const auto [slot, inserted] = members.emplace(key, nullptr);
    if (!inserted) throw InputError(prefix(pending_path()) + "key given twice in the same object");
    object.member = &slot->second;
    return true;
  }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(json::value_t::array); }
  bool end_array() { return close(); }

  template <class Exception>
  bool parse_error(std::size_t byte, const std::string& token, const Exception& e) {
    // 406: a number literal beyond the range of double ("1e999").
    if (e.id == 406) overflow(token);
    const std::string reason = parse_error_reason(e.what());
    throw InputError(file_ + ":" + line_and_column(text_, byte) + ": invalid JSON: " +
                     printable(reason, 2 * kMaxQuotedChars) + syntax_hint(text_, byte, token));
  }

 private:
  struct Open {
    json* value;             // the array or object
    std::string key;         // objects: the key of the member being read
    json* member = nullptr;  // objects: that member
  };

  template <typename Value>
  json* place(Value&& value) {
    if (open_.empty()) {
      root_ = json(std::forward<Value>(value));
      return &root_;
    }
    Open& parent = open_.back();
    if (parent.value->is_array()) {
      auto& elements = parent.value->get_ref<json::array_t&>();
      elements.emplace_back(std::forward<Value>(value));
      return &elements.back();
    }
    *parent.member = json(std::forward<Value>(value));
    return parent.member;
  }
  template <typename Value>
  bool add(Value&& value) {
    place(std::forward<Value>(value));
    return true;
  }

  bool open(json::value_t type) {
    if (open_.size() >= kMaxJsonDepth)
      throw InputError(prefix(pending_path()) + "arrays and objects nested deeper than " +
                       std::to_string(kMaxJsonDepth) + " levels");
    json* value = place(type);
    open_.push_back({value, {}, nullptr});
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }

  [[noreturn]] void overflow(const std::string& literal) const {
    throw InputError(prefix(pending_path()) + "number " + printable(literal, 40) +
                     " out of range (it overflows to infinity)");
  }

  // The path of the value being read: in an array still open below the top
  // its last element, in the top array the next one.
  std::string pending_path() const {
    std::string path;
    for (std::size_t level = 0; level < open_.size(); ++level) {
      const Open& o = open_[level];
      if (o.value->is_array()) {
        const std::size_t size = o.value->size();
        const bool top = level + 1 == open_.size();
        path += "[" + std::to_string(top ? size : size - 1) + "]";
      } else {
        path += (path.empty() ? "" : ".") + o.key;
      }
    }
    return path;
  }

  // "FILE: PATH: " ("FILE: " for the document).
  std::string prefix(const std::string& path) const {
    return file_ + ": " + (path.empty() ? "" : printable(path) + ": ");
  }

  json& root_;
  const std::string& text_;
  const std::string& file_;
  std::vector<Open> open_;
};

}  // namespace

nlohmann::json parse_json(const std::string& text, const std::string& file) {
  nlohmann::json document;
  DocumentBuilder builder(document, text, file);
  nlohmann::json::sax_parse(text, &builder);
  return document;
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
      return "a string (" + quoted(printable(v.get_ref<const std::string&>(), 40)) + ")";
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
    const std::string where = path_.empty() ? "at the top level" : "in " + path_;
    std::string message = file_ + ": unknown key " + quoted(printable(key)) + " " + where;
    // A suggestion is at most a third of the key away; a key that long is
    // no misspelling of a valid one (and its distances would be costly).
    const int close_enough = std::max(2, static_cast<int>(key.size()) / 3);
    const std::string* closest = nullptr;
    int closest_distance = INT_MAX;
    if (key.size() <= 64)
      for (const std::string& candidate : valid)
        if (const int d = edit_distance(key, candidate); d < closest_distance) {
          closest = &candidate;
          closest_distance = d;
        }
    if (closest && closest_distance <= close_enough)
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
  fail(quoted(printable(given, 40)) + " is not a valid choice; expected one of " +
       quoted_list(valid));
}

}  // namespace xshell
