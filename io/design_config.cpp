#include "design_config.hpp"

#include <nlohmann/json.hpp>

#include "config_values.hpp"
#include "json_field.hpp"

namespace xshell {

namespace {

DesignWeightsConfig read_weights(const JsonField& f) {
  f.check_keys({"fit", "deployed_energy", "flat_energy", "regularization"});
  DesignWeightsConfig w;
  for (auto [key, value] :
       {std::pair{"fit", &w.fit}, std::pair{"deployed_energy", &w.deployed_energy},
        std::pair{"flat_energy", &w.flat_energy}, std::pair{"regularization", &w.regularization}})
    if (auto field = f.find(key)) *value = non_negative(*field);
  if (w.fit + w.deployed_energy + w.flat_energy + w.regularization == 0.0)
    f.fail("every weight is 0: nothing to minimize (give at least one > 0)");
  return w;
}

}  // namespace

DesignConfig read_design(const JsonField& f, const std::string& base_dir) {
  f.check_keys({"average_opening_angle", "target_joints", "target_surface", "weights", "bounds",
                "max_iterations", "steps", "flat_planar"});
  DesignConfig d;
  d.average_opening_angle = angle(f.require("average_opening_angle"));
  const auto joints = f.find("target_joints");
  const auto surface = f.find("target_surface");
  if (joints && surface)
    f.fail("gives both \"target_joints\" and \"target_surface\"; give only one");
  if (!joints && !surface)
    f.fail("needs a target: \"target_joints\" or \"target_surface\" (exactly one of them)");
  if (joints) d.target_joints = file_path(*joints, base_dir);
  if (surface) d.target_surface = file_path(*surface, base_dir);
  if (auto weights = f.find("weights")) d.weights = read_weights(*weights);
  if (auto bounds = f.find("bounds")) d.bounds = inside(*bounds, 0, 1, "(0, 1)");
  if (auto n = f.find("max_iterations")) d.max_iterations = at_least(*n, 1);
  if (auto n = f.find("steps")) d.steps = at_least(*n, 1);
  if (auto planar = f.find("flat_planar")) d.flat_planar = toggle(*planar);
  return d;
}

nlohmann::json design_json(const DesignConfig& d) {
  nlohmann::json j = {
      {"average_opening_angle", d.average_opening_angle},
      {"weights",
       {{"fit", d.weights.fit},
        {"deployed_energy", d.weights.deployed_energy},
        {"flat_energy", d.weights.flat_energy},
        {"regularization", d.weights.regularization}}},
      {"bounds", d.bounds},
      {"max_iterations", d.max_iterations},
      {"steps", d.steps},
      {"flat_planar", d.flat_planar == Toggle::Auto ? nlohmann::json("auto")
                                                    : nlohmann::json(d.flat_planar == Toggle::On)}};
  if (!d.target_joints.empty()) j["target_joints"] = d.target_joints;
  if (!d.target_surface.empty()) j["target_surface"] = d.target_surface;
  return j;
}

}  // namespace xshell
