// The "design" section of the configuration (io/config.hpp,
// io/design_config.hpp): defaults, paths resolved, written back, and every
// bad value rejected with its key.
#include <doctest/doctest.h>

#include "config_test_support.hpp"

namespace xshell::test {

namespace {

const json kDesign = {{"average_opening_angle", 1.5}, {"target_surface", "shell.obj"}};

}  // namespace

TEST_CASE("config: design is optional, has documented defaults and is written back") {
  CHECK_FALSE(parse(kMinimal).design);
  CHECK_FALSE(to_json(parse(kMinimal)).contains("design"));
  const Config c = parse(with("/design", kDesign));
  REQUIRE(c.design);
  const DesignConfig& d = *c.design;
  CHECK(d.average_opening_angle == 1.5);
  CHECK(d.target_surface == "/runs/a/shell.obj");  // relative to the configuration's folder
  CHECK(d.target_joints.empty());
  CHECK(d.weights.fit == 1.0);
  CHECK(d.weights.deployed_energy == 0.0);
  CHECK(d.weights.flat_energy == 0.0);
  CHECK(d.weights.regularization == 0.0);
  CHECK(d.bounds == 0.2);
  CHECK(d.max_iterations == 100);
  CHECK(d.steps == 10);
  CHECK(d.flat_planar == Toggle::Auto);
  const json resolved = to_json(c);
  CHECK(resolved["design"]["flat_planar"] == "auto");
  CHECK(to_json(parse_config(resolved.dump(), "again.json", "/elsewhere")) == resolved);

  json full = kDesign;
  full.erase("target_surface");
  full["target_joints"] = "/abs/targets.json";
  full["weights"] = {
      {"fit", 2}, {"deployed_energy", 0.5}, {"flat_energy", 0.25}, {"regularization", 1e-3}};
  full["bounds"] = 0.05;
  full["max_iterations"] = 7;
  full["steps"] = 3;
  full["flat_planar"] = false;
  const Config f = parse(with("/design", full));
  CHECK(f.design->target_joints == "/abs/targets.json");
  CHECK(f.design->weights.deployed_energy == 0.5);
  CHECK(f.design->weights.flat_energy == 0.25);
  CHECK(f.design->weights.regularization == 1e-3);
  CHECK(f.design->bounds == 0.05);
  CHECK(f.design->max_iterations == 7);
  CHECK(f.design->steps == 3);
  CHECK(f.design->flat_planar == Toggle::Off);
  CHECK(to_json(parse(to_json(f).dump())) == to_json(f));
}

TEST_CASE("config: bad design values are rejected with their key") {
  auto design_with = [](const std::string& key, const json& value) {
    json d = kDesign;
    d[key] = value;
    return with("/design", d);
  };
  check_message(rejection(with("/design", json{{"target_surface", "s.obj"}})),
                {"design", "average_opening_angle"});
  check_message(rejection(design_with("average_opening_angle", 3.5)),
                {"design.average_opening_angle", "(0, pi)"});
  check_message(rejection(with("/design", json{{"average_opening_angle", 1}})),
                {"design", "needs a target"});
  check_message(rejection(design_with("target_joints", "t.json")), {"design", "gives both"});
  check_message(rejection(design_with("target_surface", "")),
                {"design.target_surface", "empty string"});
  check_message(rejection(design_with("bounds", 0)), {"design.bounds", "(0, 1)"});
  check_message(rejection(design_with("bounds", 1)), {"design.bounds", "(0, 1)"});
  check_message(rejection(design_with("max_iterations", 0)), {"design.max_iterations", ">= 1"});
  check_message(rejection(design_with("steps", 2.5)), {"design.steps"});
  check_message(rejection(design_with("flat_planar", "yes")), {"design.flat_planar"});
  check_message(rejection(design_with("weights", json{{"fit", -1}})),
                {"design.weights.fit", ">= 0"});
  check_message(rejection(design_with("weights", json{{"fit", 0}})),
                {"design.weights", "every weight is 0"});
  check_message(rejection(design_with("weights", json{{"energy", 1}})),
                {"design.weights", "energy"});
  check_message(rejection(design_with("target", "s.obj")), {"design", "target"});
}

}  // namespace xshell::test
