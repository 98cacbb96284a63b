// The fabrication files (io/fabrication_file.hpp, io/fabrication_svg.hpp):
// the JSON contract's keys and values, the CSV's rows, a well-formed SVG
// with one hole per joint station, atomic writes.
#include "io/fabrication_file.hpp"

#include <doctest/doctest.h>
#include <expat.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/fabrication_svg.hpp"
#include "io/obj_reader.hpp"
#include "io/output_error.hpp"
#include "scratch_directory.hpp"

namespace xshell::test {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

LinkageOptions options(RestShape rest = RestShape::Straight) {
  LinkageOptions o;
  o.subdivisions = 5;
  o.rest_shape = rest;
  o.material.young_modulus = 1e4;
  o.material.section = {SectionShape::Rectangle, 0.01, 0.007};
  return o;
}

RodLinkage sample_grid() {
  return RodLinkage(read_obj((fs::path(XSHELL_SAMPLES_DIR) / "grid.obj").string()), options());
}

// A rod through a valence-3 joint and a second rod ending there: ends with
// and without a vertex.
RodLinkage tee() {
  LineGraph g;
  g.vertices = {{0, 0, 0}, {-1, 0.1, 0}, {1.1, 0, 0.2}, {0.2, 1.0, -0.1}};
  g.edges = {{1, 0}, {0, 2}, {0, 3}};
  return RodLinkage(g, options(RestShape::Input));
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> out(1);
  for (char c : text) {
    if (c == separator)
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

// The elements of an XML document as parsed by expat: name and attributes.
struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
};
struct ParsedXml {
  bool well_formed = false;
  std::string error;
  std::vector<Element> elements;
};

ParsedXml parse_xml(const std::string& text) {
  ParsedXml out;
  XML_Parser parser = XML_ParserCreate("UTF-8");
  XML_SetUserData(parser, &out);
  XML_SetStartElementHandler(parser, [](void* data, const XML_Char* name, const XML_Char** atts) {
    Element e;
    e.name = name;
    for (int k = 0; atts[k]; k += 2) e.attributes[atts[k]] = atts[k + 1];
    static_cast<ParsedXml*>(data)->elements.push_back(e);
  });
  out.well_formed =
      XML_Parse(parser, text.data(), static_cast<int>(text.size()), 1) == XML_STATUS_OK;
  if (!out.well_formed) out.error = XML_ErrorString(XML_GetErrorCode(parser));
  XML_ParserFree(parser);
  return out;
}

}  // namespace

TEST_CASE("fabrication.json: the contract's keys and units and values") {
  const RodLinkage linkage = sample_grid();
  const FabricationData data = fabrication_data(linkage);
  const json j = fabrication_json(data, FabricationUnits{"length unit of grid.obj"});
  CHECK(j["format"] == "xshell-fabrication");
  CHECK(j["version"] == 1);
  CHECK(j["units"]["length"] == "length unit of grid.obj");
  CHECK(j["units"]["angle"] == "radian");
  REQUIRE(j["rods"].size() == data.rods.size());
  REQUIRE(j["joints"].size() == data.joints.size());
  int checked = 0;
  for (size_t r = 0; r < data.rods.size(); ++r) {
    const json& rod = j["rods"][r];
    for (const char* key :
         {"rod", "family", "length", "closed", "cross_section", "stations", "other_label_joints"})
      CHECK(rod.contains(key));
    CHECK(rod["rod"] == static_cast<int>(r));
    CHECK(rod["family"] == family_name(data.rods[r].family));
    CHECK(rod["length"].get<double>() == data.rods[r].length);  // exact: round trip
    CHECK(rod["cross_section"]["shape"] == "rectangle");
    CHECK(rod["cross_section"]["width"].get<double>() == 0.01);
    CHECK(rod["cross_section"]["height"].get<double>() == 0.007);
    REQUIRE(rod["stations"].size() == data.rods[r].stations.size());
    for (size_t k = 0; k < data.rods[r].stations.size(); ++k) {
      const json& st = rod["stations"][k];
      const RodStation& expected = data.rods[r].stations[k];
      CHECK(st["s"].get<double>() == expected.s);
      CHECK(st["vertex"].get<int>() == expected.vertex);  // the grid's rods end at free ends
      CHECK(st["kind"] == (expected.kind == StationKind::End ? "end" : "joint"));
      ++checked;
    }
  }
  for (size_t k = 0; k < data.joints.size(); ++k) {
    const json& joint = j["joints"][k];
    for (const char* key : {"vertex", "valence", "rods", "stations", "angle_input", "angle"})
      CHECK(joint.contains(key));
    CHECK(joint["vertex"] == data.joints[k].vertex);
    CHECK(joint["rods"] == json::array({data.joints[k].rod[0], data.joints[k].rod[1]}));
    CHECK(joint["stations"][0].get<double>() == data.joints[k].s[0]);
    CHECK(joint["stations"][1].get<double>() == data.joints[k].s[1]);
    CHECK(joint["angle_input"].get<double>() == data.joints[k].angle_input);
    CHECK(joint["angle"].get<double>() == data.joints[k].angle);
    ++checked;
  }
  CHECK(checked == 8 * 6 + 16);
}

TEST_CASE("fabrication.json: an end that is no vertex is null") {
  const FabricationData data = fabrication_data(tee());
  const json j = fabrication_json(data, FabricationUnits{});
  CHECK(j["units"]["length"] == "length unit of the linkage file");
  int nulls = 0;
  for (const json& rod : j["rods"])
    for (const json& st : rod["stations"]) nulls += st["vertex"].is_null();
  CHECK(nulls == 1);  // the tee's ending rod's overhang
}

TEST_CASE("fabrication.csv: one row per station with the documented columns") {
  const FabricationData data = fabrication_data(tee());
  const std::string csv = fabrication_csv(data);
  std::vector<std::string> lines = split(csv, '\n');
  REQUIRE(lines.back().empty());  // ends with a newline
  lines.pop_back();
  REQUIRE(!lines.empty());
  CHECK(lines[0] == "rod,family,kind,vertex,s,rod_length");
  size_t row = 1;
  for (const FabricationRod& rod : data.rods)
    for (const RodStation& st : rod.stations) {
      REQUIRE(row < lines.size());
      const std::vector<std::string> cells = split(lines[row++], ',');
      REQUIRE(cells.size() == 6);
      CHECK(cells[0] == std::to_string(rod.rod));
      CHECK(cells[1] == family_name(rod.family));
      CHECK(cells[2] == (st.kind == StationKind::End ? "end" : "joint"));
      CHECK(cells[3] == (st.vertex >= 0 ? std::to_string(st.vertex) : ""));
      // 12 significant digits.
      CHECK(std::stod(cells[4]) == doctest::Approx(st.s).epsilon(1e-11));
      CHECK(std::stod(cells[5]) == doctest::Approx(rod.length).epsilon(1e-11));
    }
  CHECK(row == lines.size());
  CHECK(row == 1 + 3 + 3);  // each rod: two ends and the joint
}

TEST_CASE("fabrication.svg: well-formed XML with one lath per rod and one hole per joint station") {
  for (const RodLinkage& linkage : {sample_grid(), tee()}) {
    const FabricationData data = fabrication_data(linkage);
    const std::string svg = fabrication_svg(data, FabricationUnits{"unit <&> of \"x\""});
    const ParsedXml xml = parse_xml(svg);
    CAPTURE(xml.error);
    REQUIRE(xml.well_formed);
    REQUIRE(!xml.elements.empty());
    CHECK(xml.elements[0].name == "svg");
    CHECK(xml.elements[0].attributes.at("xmlns") == "http://www.w3.org/2000/svg");
    std::multiset<std::pair<int, int>> holes, stations;  // (rod, vertex)
    int laths = 0, scale_bars = 0;
    for (const Element& e : xml.elements) {
      const auto c = e.attributes.find("class");
      if (c == e.attributes.end()) continue;
      if (c->second == "hole") {
        CHECK(e.name == "circle");
        holes.insert(
            {std::stoi(e.attributes.at("data-rod")), std::stoi(e.attributes.at("data-vertex"))});
      }
      laths += c->second == "lath";
      scale_bars += c->second == "scale-bar";
    }
    for (const FabricationRod& rod : data.rods)
      for (const RodStation& st : rod.stations)
        if (st.kind == StationKind::Joint) stations.insert({rod.rod, st.vertex});
    CHECK(holes == stations);
    CHECK(holes.size() == 2 * data.joints.size());
    CHECK(laths == static_cast<int>(data.rods.size()));
    CHECK(scale_bars == 1);
    // The unit is named (escaped) in the title and the scale bar.
    CHECK(svg.find("unit &lt;&amp;&gt; of &quot;x&quot;") != std::string::npos);
  }
}

TEST_CASE("write_fabrication: the three files written atomically into an existing directory") {
  const ScratchDirectory scratch("fabrication");
  const fs::path& dir = scratch.path();
  const RodLinkage linkage = sample_grid();
  write_fabrication(linkage, FabricationUnits{}, dir);
  const json j = json::parse(read_text(dir / "fabrication.json"));
  CHECK(j == fabrication_json(fabrication_data(linkage), FabricationUnits{}));
  CHECK(read_text(dir / "fabrication.csv") == fabrication_csv(fabrication_data(linkage)));
  CHECK(parse_xml(read_text(dir / "fabrication.svg")).well_formed);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    CHECK(!is_temporary_file_name(entry.path().filename().string()));
    ++files;
  }
  CHECK(files == 3);
  CHECK_THROWS_AS(write_fabrication(linkage, FabricationUnits{}, dir / "missing"), OutputError);
}

TEST_CASE("fabrication_units: named after the configuration's linkage file") {
  Config config;
  config.linkage = "/some/where/grid_mm.obj";
  CHECK(fabrication_units(config).length == "length unit of grid_mm.obj");
  CHECK(fabrication_units(config).angle == "radian");
}

}  // namespace xshell::test
