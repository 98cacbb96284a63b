#include "unit_names.hpp"

#include <cctype>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

namespace xshell {

namespace {
bool word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
}  // namespace

std::string unit_label(const std::string& dimension, const UnitNames& names) {
  static const std::map<std::string, std::string> kStresses = {
      {"N/mm^2", "MPa"}, {"N/m^2", "Pa"}, {"kN/m^2", "kPa"}, {"MN/m^2", "MPa"}};
  std::string out;
  for (std::size_t i = 0; i < dimension.size();) {
    if (!word_char(dimension[i])) {
      out += dimension[i++];
      continue;
    }
    std::size_t end = i;
    while (end < dimension.size() && word_char(dimension[end])) ++end;
    const std::string word = dimension.substr(i, end - i);
    if (word == "length" && !names.length.empty())
      out += names.length;
    else if (word == "force" && !names.force.empty())
      out += names.force;
    else
      out += word;
    i = end;
  }
  const auto named = kStresses.find(out);
  return named == kStresses.end() ? out : named->second;
}

UnitNames run_unit_names(const std::filesystem::path& folder) {
  UnitNames names;
  std::ifstream in(folder / "summary.json", std::ios::binary);
  if (!in) return names;
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (!summary.is_object()) return names;
  const auto configuration = summary.find("configuration");
  if (configuration == summary.end() || !configuration->is_object()) return names;
  const auto units = configuration->find("units");
  if (units == configuration->end() || !units->is_object()) return names;
  for (auto [key, name] : {std::pair{"length", &names.length}, std::pair{"force", &names.force}})
    if (const auto it = units->find(key); it != units->end() && it->is_string())
      *name = it->get<std::string>();
  return names;
}

}  // namespace xshell
