// Unit names: the configuration's "units", the labels made of them and the
// units a run's summary records.
#include "io/unit_names.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/config.hpp"
#include "io/input_error.hpp"
#include "scratch_directory.hpp"

namespace xshell::test {

TEST_CASE("unit_label: configured names replace the words length and force") {
  const UnitNames mm{"mm", "N"}, m{"m", "kN"}, none;
  CHECK(unit_label("force length/rad", mm) == "N mm/rad");
  CHECK(unit_label("force/length^2", mm) == "MPa");
  CHECK(unit_label("force/length^2", UnitNames{"m", "N"}) == "Pa");
  CHECK(unit_label("force/length^2", m) == "kPa");
  CHECK(unit_label("force/length^2", UnitNames{"in", "lbf"}) == "lbf/in^2");
  CHECK(unit_label("1/length", mm) == "1/mm");
  CHECK(unit_label("rad/length", m) == "rad/m");
  CHECK(unit_label("force length", none) == "force length");
  CHECK(unit_label("force/length^2", UnitNames{"mm", ""}) == "force/mm^2");
  CHECK(unit_label("lengths", mm) == "lengths");  // whole words only
}

TEST_CASE("config: the units key is read and written back and checked") {
  const std::string base =
      R"({"linkage": "g.obj", "material": {"young_modulus": 1, "cross_section": {"width": 1, "height": 1}})";
  const Config plain = parse_config(base + "}", "c.json", "");
  CHECK(plain.units.length.empty());
  CHECK(plain.units.force.empty());
  CHECK_FALSE(to_json(plain).contains("units"));
  const Config c =
      parse_config(base + R"(, "units": {"length": "mm", "force": "N"}})", "c.json", "");
  CHECK(c.units.length == "mm");
  CHECK(c.units.force == "N");
  CHECK(to_json(c)["units"] == nlohmann::json({{"length", "mm"}, {"force", "N"}}));
  const Config length_only = parse_config(base + R"(, "units": {"length": "m"}})", "c.json", "");
  CHECK(length_only.units.length == "m");
  CHECK(length_only.units.force.empty());
  struct Case {
    std::string units, words;
  };
  const std::vector<Case> cases = {
      {R"({"length": "milli metre"})", "units.length: must be a unit's name"},
      {R"({"force": ""})", "units.force: must be a unit's name"},
      {R"({"force": "N/m"})", "units.force"},
      {R"({"length": "a_very_long_unit_name"})", "units.length"},
      {R"({"length": 1})", "units.length"},
      {R"({"mass": "kg"})", "mass"},
  };
  for (const Case& k : cases) {
    CAPTURE(k.units);
    CHECK_THROWS_WITH_AS(parse_config(base + ", \"units\": " + k.units + "}", "c.json", ""),
                         doctest::Contains(k.words.c_str()), InputError);
  }
}

TEST_CASE("run_unit_names: the units of the configuration in a run's summary.json") {
  namespace fs = std::filesystem;
  const ScratchDirectory scratch("unit-names");
  const fs::path& dir = scratch.path();
  CHECK(run_unit_names(dir).length.empty());  // no summary
  std::ofstream(dir / "summary.json") << "{not json";
  CHECK(run_unit_names(dir).force.empty());
  std::ofstream(dir / "summary.json")
      << R"({"configuration": {"units": {"length": "mm", "force": "kN"}}})";
  CHECK(run_unit_names(dir).length == "mm");
  CHECK(run_unit_names(dir).force == "kN");
}

}  // namespace xshell::test
