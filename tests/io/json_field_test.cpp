#include "io/json_field.hpp"

#include <doctest/doctest.h>

#include "io/input_error.hpp"

namespace xshell::test {

TEST_CASE("json_field: edit_distance is the Levenshtein distance") {
  struct Case {
    const char *a, *b;
    int distance;
  };
  const Case cases[] = {{"", "", 0},
                        {"", "abc", 3},
                        {"abc", "", 3},
                        {"kitten", "sitting", 3},
                        {"young_modulous", "young_modulus", 1},
                        {"hieght", "height", 2},
                        {"flaw", "lawn", 2},
                        {"same", "same", 0}};
  int checked = 0;
  for (const Case& c : cases) {
    INFO(c.a << " -> " << c.b);
    CHECK(edit_distance(c.a, c.b) == c.distance);
    CHECK(edit_distance(c.b, c.a) == c.distance);
    ++checked;
  }
  CHECK(checked == 8);
}

TEST_CASE("json_field: parse_json reports paths through nested arrays and objects") {
  CHECK_THROWS_WITH_AS(parse_json(R"({"a": [[1, 2], [3, 1e999]]})", "f.json"),
                       "f.json: a[1][1]: number 1e999 out of range (it overflows to infinity)",
                       InputError);
  CHECK_THROWS_WITH_AS(parse_json(R"({"s": [{"v": 1}, {"w": [], "v": 1, "v": 2}]})", "f.json"),
                       "f.json: s[1].v: key given twice in the same object", InputError);
  CHECK_THROWS_WITH_AS(parse_json("-1e400", "f.json"),
                       "f.json: number -1e400 out of range (it overflows to infinity)", InputError);
  // The same key in sibling objects is fine.
  const auto document = parse_json(R"({"s": [{"v": 1}, {"v": 2}], "t": {"v": 3}})", "f.json");
  CHECK(document["t"]["v"] == 3);
}

TEST_CASE("json_field: syntax errors count lines and columns from 1") {
  CHECK_THROWS_WITH_AS(parse_json("{\"a\": 1}\n\n  x", "f.json"), doctest::Contains("f.json:3:3:"),
                       InputError);
  CHECK_THROWS_WITH_AS(parse_json("{\"a\": tru}", "f.json"), doctest::Contains("f.json:1:"),
                       InputError);
}

TEST_CASE("json_field: accessors check types and name the path") {
  const nlohmann::json document = {{"n", 2.5}, {"list", {1, 2}}, {"s", "text"}};
  const JsonField root(document, "", "f.json");
  CHECK(root.require("n").number() == 2.5);
  CHECK_THROWS_WITH_AS(root.require("n").integer(),
                       "f.json: n: expected an integer, got a number (2.5)", InputError);
  CHECK_THROWS_WITH_AS(root.require("s").number(),
                       "f.json: s: expected a number, got a string (\"text\")", InputError);
  const auto items = root.require("list").elements();
  REQUIRE(items.size() == 2);
  CHECK(items[1].path() == "list[1]");
  CHECK(items[1].integer() == 2);
  CHECK_THROWS_WITH_AS(items[0].string(), "f.json: list[0]: expected a string, got a number (1)",
                       InputError);
  CHECK_THROWS_WITH_AS(root.require("missing"), "f.json: missing required key \"missing\"",
                       InputError);
  CHECK_FALSE(root.find("missing").has_value());
}

}  // namespace xshell::test
