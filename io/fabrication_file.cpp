#include "io/fabrication_file.hpp"

#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/fabrication_svg.hpp"

namespace xshell {

namespace {

const char* kind_name(StationKind kind) { return kind == StationKind::End ? "end" : "joint"; }

const char* shape_name(SectionShape shape) {
  return shape == SectionShape::Rectangle ? "rectangle" : "ellipse";
}

// 12 significant digits: far below any workshop's tolerance, and free of
// the round-off digits (0.9999999999999996) that the JSON keeps.
std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return buffer;
}

}  // namespace

FabricationUnits fabrication_units(const Config& config) {
  FabricationUnits units;
  if (!config.linkage.empty())
    units.length = "length unit of " + std::filesystem::path(config.linkage).filename().string();
  if (config.transform.scale != 1.0)
    units.length += " x " + number(config.transform.scale) + " (the \"transform\" scale)";
  return units;
}

nlohmann::json fabrication_json(const FabricationData& data, const FabricationUnits& units) {
  using nlohmann::json;
  json rods = json::array(), joints = json::array();
  for (const FabricationRod& rod : data.rods) {
    json stations = json::array();
    for (const RodStation& st : rod.stations)
      stations.push_back({{"kind", kind_name(st.kind)},
                          {"vertex", st.vertex >= 0 ? json(st.vertex) : json(nullptr)},
                          {"s", st.s}});
    rods.push_back({{"rod", rod.rod},
                    {"family", family_name(rod.family)},
                    {"length", rod.length},
                    {"closed", rod.closed},
                    {"cross_section",
                     {{"shape", shape_name(rod.section.shape)},
                      {"width", rod.section.width},
                      {"height", rod.section.height}}},
                    {"stations", stations},
                    {"other_label_joints", rod.other_label_vertices}});
  }
  for (const FabricationJoint& joint : data.joints)
    joints.push_back({{"vertex", joint.vertex},
                      {"valence", joint.valence},
                      {"rods", {joint.rod[0], joint.rod[1]}},
                      {"stations", {joint.s[0], joint.s[1]}},
                      {"angle_input", joint.angle_input},
                      {"angle", joint.angle}});
  return {{"format", "xshell-fabrication"},
          {"version", 1},
          {"units", {{"length", units.length}, {"angle", units.angle}}},
          {"rods", rods},
          {"joints", joints}};
}

std::string fabrication_csv(const FabricationData& data) {
  std::string out = "rod,family,kind,vertex,s,rod_length\n";
  for (const FabricationRod& rod : data.rods)
    for (const RodStation& st : rod.stations) {
      out += std::to_string(rod.rod) + "," + family_name(rod.family) + "," + kind_name(st.kind) +
             "," + (st.vertex >= 0 ? std::to_string(st.vertex) : "") + "," + number(st.s) + "," +
             number(rod.length) + "\n";
    }
  return out;
}

void write_fabrication_files(const FabricationData& data, const FabricationUnits& units,
                             const std::filesystem::path& dir) {
  write_file_atomically(dir / "fabrication.json", fabrication_json(data, units).dump(2) + "\n");
  write_file_atomically(dir / "fabrication.csv", fabrication_csv(data));
  write_file_atomically(dir / "fabrication.svg", fabrication_svg(data, units));
}

void write_fabrication(const RodLinkage& linkage, const FabricationUnits& units,
                       const std::filesystem::path& dir) {
  write_fabrication_files(fabrication_data(linkage), units, dir);
}

}  // namespace xshell
