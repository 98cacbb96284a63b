// What the configuration reader's tests share: a minimal configuration,
// edits of it, and the message of a rejected one.
#pragma once

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/input_error.hpp"

namespace xshell::test {

using nlohmann::json;

inline const json kMinimal = {
    {"linkage", "grid.obj"},
    {"material", {{"young_modulus", 2e4}, {"cross_section", {{"width", 10}, {"height", 7}}}}}};

inline Config parse(const std::string& text) { return parse_config(text, "c.json", "/runs/a"); }
inline Config parse(const json& document) { return parse(document.dump()); }

// kMinimal with the value at JSON `pointer` set (or removed when `value` is
// discarded).
inline json with(const std::string& pointer, const json& value) {
  json document = kMinimal;
  const json::json_pointer p(pointer);
  if (value.is_discarded())
    document[p.parent_pointer()].erase(p.back());
  else
    document[p] = value;
  return document;
}
inline json without(const std::string& pointer) {
  return with(pointer, json(json::value_t::discarded));
}

// The message of the InputError that `text` raises; a failed check and ""
// when it is accepted or raises anything else.
inline std::string rejection(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  } catch (...) {
    FAIL_CHECK("not an InputError");
    return "";
  }
  FAIL_CHECK("accepted: " << text);
  return "";
}
inline std::string rejection(const json& document) { return rejection(document.dump()); }

// Checks that `message` names the file and contains every one of `words`.
inline void check_message(const std::string& message, const std::vector<std::string>& words) {
  INFO("message: " << message);
  CHECK(message.rfind("c.json", 0) == 0);
  for (const auto& w : words) CHECK_MESSAGE(message.find(w) != std::string::npos, "missing: " << w);
}

}  // namespace xshell::test
