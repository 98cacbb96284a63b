// Reading and writing the "design" section of a configuration (DesignConfig,
// config.hpp), as config.cpp does the other sections.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "config.hpp"

namespace xshell {

class JsonField;

DesignConfig read_design(const JsonField& f, const std::string& base_dir);
nlohmann::json design_json(const DesignConfig& d);

}  // namespace xshell
