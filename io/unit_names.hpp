// The names of a run's unit system, for labels only: the configuration's
// "units" ({"length": "mm", "force": "N"}, each optional). The model has no
// units of its own (config.hpp); the files say a quantity's unit in the words
// "length" and "force" (e.g. a stress is "force/length^2"), and a label puts
// the configured names in their place.
#pragma once

#include <filesystem>
#include <string>

namespace xshell {

struct UnitNames {
  std::string length;  // e.g. "mm"; empty: not configured
  std::string force;   // e.g. "N"; empty: not configured
};

// `dimension` with every word "length" and "force" replaced by its
// configured name (unconfigured ones stay words): "force length/rad" with mm
// and N is "N mm/rad". A stress in N and mm is named MPa (N and m: Pa, kN
// and m: kPa).
std::string unit_label(const std::string& dimension, const UnitNames& names);

// The units of the configuration recorded in `folder`/summary.json (its
// "configuration"."units"); empty names when the file is missing, cannot be
// parsed or has none.
UnitNames run_unit_names(const std::filesystem::path& folder);

}  // namespace xshell
