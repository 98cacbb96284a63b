#include "target_joints_file.hpp"

#include "input_error.hpp"
#include "input_file.hpp"
#include "json_field.hpp"

namespace xshell {

int TargetJoints::count() const {
  int n = 0;
  for (const auto& p : positions) n += p.has_value();
  return n;
}

TargetJoints parse_target_joints(const std::string& text, const std::string& file,
                                 int num_vertices) {
  const nlohmann::json doc = parse_json(text, file);
  const JsonField root(doc, "", file);
  root.check_keys({"positions"});
  const JsonField list = root.require("positions");
  const std::vector<JsonField> entries = list.elements();
  if (static_cast<int>(entries.size()) != num_vertices)
    list.fail(std::to_string(entries.size()) + " entries for a linkage of " +
              std::to_string(num_vertices) +
              " vertices: give one per vertex of the OBJ file, in its order (null for none)");
  TargetJoints targets;
  for (const JsonField& entry : entries)
    targets.positions.push_back(entry.is_null() ? std::nullopt
                                                : std::optional<Eigen::Vector3d>(entry.vector3()));
  if (targets.count() == 0) list.fail("every entry is null: no vertex has a target");
  return targets;
}

TargetJoints read_target_joints(const std::string& path, int num_vertices) {
  const std::string shown = printable(path);
  const std::string text =
      read_input_file(path, kConfigurationFile, "cannot open target joints file '" + shown + "'");
  return parse_target_joints(text, shown, num_vertices);
}

}  // namespace xshell
