// Checked reading of a user's JSON document. A JsonField is one value of the
// document together with its JSON path ("material.cross_section.width",
// "supports[2].fix[0]"); every accessor checks the value's type (and that
// numbers are finite) and throws one InputError "FILE: PATH: what is wrong".
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace xshell {

// Deepest nesting of arrays and objects parse_json accepts (a configuration
// nests 5 levels deep, a state file 6).
constexpr std::size_t kMaxJsonDepth = 64;

// Parses `text` as JSON, in time linear in its length. Syntax errors are
// reported as "FILE:LINE:COLUMN: ...", a key repeated within one object,
// non-finite numbers (a literal such as 1e999 overflows to infinity) and
// nesting deeper than kMaxJsonDepth with their path. `file` is the file's
// name as messages show it (see printable()).
nlohmann::json parse_json(const std::string& text, const std::string& file);

// Levenshtein distance: the fewest single-character insertions, deletions
// and substitutions that turn `a` into `b`.
int edit_distance(const std::string& a, const std::string& b);

class JsonField {
 public:
  // `value` must outlive the field and every field taken from it.
  JsonField(const nlohmann::json& value, std::string path, std::string file);

  const nlohmann::json& value() const { return *value_; }
  const std::string& path() const { return path_; }  // "" for the document itself

  // Throws InputError "FILE: PATH: what" ("FILE: what" for the document).
  [[noreturn]] void fail(const std::string& what) const;

  // Objects. check_keys fails unless the value is an object whose keys are
  // all in `valid`, suggesting the closest valid key for an unknown one.
  void check_keys(const std::vector<std::string>& valid) const;
  std::optional<JsonField> find(const std::string& key) const;
  JsonField require(const std::string& key) const;  // fails when missing

  // Arrays: the elements, failing unless the value is an array.
  std::vector<JsonField> elements() const;

  // Scalars.
  bool is_string() const { return value_->is_string(); }
  bool is_boolean() const { return value_->is_boolean(); }
  bool is_null() const { return value_->is_null(); }
  double number() const;  // finite
  int integer() const;    // a number with an integer value that fits an int
  bool boolean() const;
  std::string string() const;
  Eigen::Vector3d vector3() const;  // [x, y, z] of finite numbers

  // A string naming one of `names`; the message lists them all.
  template <typename E>
  E choice(const std::vector<std::pair<E, std::string>>& names) const {
    const std::string s = string();
    for (const auto& [value, name] : names)
      if (s == name) return value;
    std::vector<std::string> valid;
    for (const auto& entry : names) valid.push_back(entry.second);
    fail_choice(s, valid);
  }

  // "a string (\"abc\")", "an array", ...: the value's type, for messages.
  std::string describe() const;

 private:
  [[noreturn]] void fail_choice(const std::string& given,
                                const std::vector<std::string>& valid) const;

  const nlohmann::json* value_;
  std::string path_;
  std::string file_;
};

}  // namespace xshell
