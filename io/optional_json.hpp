// How the output files write a quantity that may be absent: its value, or
// null.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

namespace xshell {

template <class T>
nlohmann::json optional_json(const std::optional<T>& x) {
  return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
}

}  // namespace xshell
