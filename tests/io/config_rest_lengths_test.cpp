// "rest_lengths" of the configuration: one rest length per segment, in the
// linkage file's edge order, read, written back, checked and handed to the
// model (io/config.hpp, io/problem_setup.hpp).
#include <doctest/doctest.h>

#include <sstream>

#include "config_test_support.hpp"
#include "io/obj_reader.hpp"
#include "io/problem_setup.hpp"

namespace xshell::test {
namespace {

// A polyline and a line: "l 1 2 3" gives the edges 0-1 and 1-2, "l 3 4" the
// edge 2-3, in this order. A bent lath (no joints), drawn 1, 2 and 3 long.
LineGraph polyline_graph() {
  std::istringstream obj("v 0 0 0\nv 1 0 0\nv 1 2 0\nv 4 2 0\nl 1 2 3\nl 3 4\n");
  return parse_obj(obj, "p.obj");
}

}  // namespace

TEST_CASE("config: rest_lengths are read, default to none and are written back") {
  CHECK(parse(kMinimal).rest_lengths.empty());
  CHECK_FALSE(to_json(parse(kMinimal)).contains("rest_lengths"));
  const Config c = parse(with("/rest_lengths", {1, 2.5, 3e-3}));
  CHECK(c.rest_lengths == std::vector<double>{1, 2.5, 3e-3});
  const json resolved = to_json(c);
  CHECK(resolved["rest_lengths"] == json({1.0, 2.5, 3e-3}));
  CHECK(to_json(parse_config(resolved.dump(), "again.json", "/elsewhere")) == resolved);
}

TEST_CASE("config: bad rest_lengths are rejected with their key") {
  check_message(rejection(with("/rest_lengths", 1.5)), {"rest_lengths", "expected an array"});
  check_message(rejection(with("/rest_lengths", json::array())),
                {"rest_lengths", "one rest length per segment", "empty array"});
  check_message(rejection(with("/rest_lengths", {1, 0})),
                {"rest_lengths[1]", "must be > 0, got 0"});
  check_message(rejection(with("/rest_lengths", {-2, 1})),
                {"rest_lengths[0]", "must be > 0, got -2"});
  check_message(rejection(with("/rest_lengths", {1, "2"})),
                {"rest_lengths[1]", "expected a number"});
  check_message(rejection(with("/rest_lengths", {1, nullptr})),
                {"rest_lengths[1]", "expected a number"});
  check_message(rejection(with("/rest_lengths", {1, {1}})),
                {"rest_lengths[1]", "expected a number"});
  // JSON has no NaN or infinity; a literal beyond the doubles overflows to
  // infinity and is refused where it stands.
  const std::string text = "{\"rest_lengths\": [1, 1e400], " + kMinimal.dump().substr(1);
  check_message(rejection(text), {"rest_lengths[1]", "infinity"});
  check_message(rejection(with("/rest_length", {1})), {"rest_length", "rest_lengths"});
}

TEST_CASE("config: rest_lengths follow the linkage file's edge order into the model") {
  const LineGraph graph = polyline_graph();
  REQUIRE(graph.edges.size() == 3);
  CHECK(graph.edges[0] == std::array<int, 2>{0, 1});
  CHECK(graph.edges[1] == std::array<int, 2>{1, 2});
  CHECK(graph.edges[2] == std::array<int, 2>{2, 3});
  int built = 0;
  for (const char* shape : {"straight", "input"}) {
    CAPTURE(shape);
    json document = with("/rest_lengths", {1.25, 2.5, 2.75});
    document["rest_shape"] = shape;
    document["subdivisions"] = 4;
    const ProblemSetup setup = make_problem_setup(parse(document), graph);
    CHECK(setup.options.segment_rest_lengths == std::vector<double>{1.25, 2.5, 2.75});
    const RodLinkage linkage(setup.graph, setup.options);
    const std::vector<double> lengths = linkage.segment_rest_lengths();
    REQUIRE(lengths.size() == 3);
    CHECK(lengths[0] == doctest::Approx(1.25).epsilon(1e-14));
    CHECK(lengths[1] == doctest::Approx(2.5).epsilon(1e-14));
    CHECK(lengths[2] == doctest::Approx(2.75).epsilon(1e-14));
    ++built;
  }
  CHECK(built == 2);
  // Without the key, the drawing's lengths (1, 2, 3).
  const ProblemSetup drawn = make_problem_setup(parse(kMinimal), graph);
  CHECK(drawn.options.segment_rest_lengths.empty());
}

TEST_CASE("config: a count of rest_lengths other than the linkage's segments is refused") {
  const LineGraph graph = polyline_graph();
  for (const json& lengths : {json({1, 2}), json({1, 2, 3, 4})}) {
    const Config c = parse(with("/rest_lengths", lengths));
    const std::string expected = "c.json: rest_lengths: " + std::to_string(lengths.size()) +
                                 " rest lengths given; the linkage has 3 segments, so it needs 3";
    CHECK_THROWS_WITH_AS(make_problem_setup(c, graph), doctest::Contains(expected.c_str()),
                         InputError);
  }
}

}  // namespace xshell::test
