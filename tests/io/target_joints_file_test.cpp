#include "io/target_joints_file.hpp"

#include <doctest/doctest.h>

#include "io/input_error.hpp"

namespace xshell::test {
namespace {

std::string rejection(const std::string& text, int vertices) {
  try {
    parse_target_joints(text, "t.json", vertices);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL_CHECK("accepted: " << text);
  return "";
}

}  // namespace

TEST_CASE("Target joints: a position or null per vertex") {
  const TargetJoints t =
      parse_target_joints(R"({"positions": [[0, 1, 2], null, [1e-3, -4, 5.5]]})", "t.json", 3);
  REQUIRE(t.positions.size() == 3);
  CHECK(t.count() == 2);
  CHECK(*t.positions[0] == Eigen::Vector3d(0, 1, 2));
  CHECK_FALSE(t.positions[1].has_value());
  CHECK(*t.positions[2] == Eigen::Vector3d(1e-3, -4, 5.5));
}

TEST_CASE("Target joints files that do not fit the linkage are refused with their path") {
  CHECK(rejection(R"({"positions": [[0, 1, 2]]})", 2) ==
        "t.json: positions: 1 entries for a linkage of 2 vertices: give one per vertex of the "
        "OBJ file, in its order (null for none)");
  CHECK(rejection(R"({"positions": [null, null]})", 2) ==
        "t.json: positions: every entry is null: no vertex has a target");
  CHECK(rejection(R"({"positions": [[0, 1], null]})", 2)
            .find("t.json: positions[0]: expected an array of three numbers") == 0);
  CHECK(rejection(R"({"positions": [[0, 1, 1e999], null]})", 2).find("t.json") == 0);
  CHECK(rejection(R"({"position": []})", 2).find("t.json: ") == 0);
  CHECK(rejection(R"({"positions": 3})", 1).find("t.json: positions: ") == 0);
  CHECK_THROWS_WITH_AS(read_target_joints("/nonexistent/targets.json", 1),
                       doctest::Contains("cannot open target joints file"), InputError);
}

}  // namespace xshell::test
