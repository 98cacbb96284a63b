#include "io/json_field.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>

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

TEST_CASE("json_field: a comment is not JSON and is reported where it starts") {
  // The error at the first byte: the column used to wrap around below 1.
  CHECK_THROWS_WITH_AS(parse_json("// a comment\n{\"a\": 1}\n", "f.json"),
                       doctest::Contains("f.json:1:1: invalid JSON"), InputError);
  CHECK_THROWS_WITH_AS(parse_json("// a comment\n{}", "f.json"),
                       doctest::Contains("JSON has no comments"), InputError);
  CHECK_THROWS_WITH_AS(parse_json("{\"a\": 1, /* two */ \"b\": 2}", "f.json"),
                       doctest::Contains("f.json:1:10: invalid JSON"), InputError);
}

TEST_CASE("json_field: nesting deeper than 64 levels is refused with its path") {
  auto nested = [](int depth) {
    std::string text;
    for (int i = 0; i < depth; ++i) text += "{\"k\": [";
    text += "1";
    for (int i = 0; i < depth; ++i) text += "]}";
    return text;
  };
  CHECK_NOTHROW(parse_json(nested(32), "f.json"));  // 64 levels
  CHECK_THROWS_WITH_AS(parse_json(nested(33), "f.json"), doctest::Contains("f.json: k[0].k[0]"),
                       InputError);
  CHECK_THROWS_WITH_AS(parse_json(nested(33), "f.json"),
                       doctest::Contains("nested deeper than 64 levels"), InputError);
  // 200 KB of '[': refused at once, not read into a document.
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH_AS(parse_json(std::string(200000, '['), "f.json"),
                       doctest::Contains("f.json: [0][0][0]"), InputError);
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(2));
}

namespace {
// Seconds to parse `text`, once.
double parse_seconds(const std::string& text) {
  const auto start = std::chrono::steady_clock::now();
  const auto document = parse_json(text, "f.json");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(document.size() == 1);
  return seconds;
}
}  // namespace

TEST_CASE("json_field: parsing time grows linearly with an array of objects") {
  // nlohmann's parse with a callback scanned the whole array again at the
  // end of each object in it: 4 times the forces took 16 times as long.
  auto forces = [](int n) {
    std::string text = "{\"forces\": [";
    for (int i = 0; i < n; ++i)
      text += std::string(i ? "," : "") + "{\"vertex\": 13, \"force\": [0, 0, -1.5]}";
    return text + "]}";
  };
  // The best of five runs of each, taken in turn, so that a busy machine
  // slows both alike.
  const std::string small_text = forces(20000), large_text = forces(80000);
  double small = 1e9, large = 1e9;
  for (int run = 0; run < 5; ++run) {
    small = std::min(small, parse_seconds(small_text));
    large = std::min(large, parse_seconds(large_text));
  }
  INFO("20000 forces: " << small << " s, 80000: " << large << " s");
  CHECK(large < 8 * small + 0.05);
}

TEST_CASE("json_field: paths are spelled only for messages") {
  // 60 levels of keys of 4000 characters with 20000 values at the bottom:
  // a path spelled per value would copy 240 KB 20000 times.
  std::string text;
  for (int i = 0; i < 60; ++i) text += "{\"" + std::string(4000, 'a' + i % 26) + "\": ";
  text += "[";
  for (int i = 0; i < 20000; ++i) text += std::string(i ? "," : "") + "1";
  text += "]" + std::string(60, '}');
  const auto start = std::chrono::steady_clock::now();
  CHECK_NOTHROW(parse_json(text, "f.json"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(2));
  // And a message quotes such a path shortened.
  const std::string bad = text.substr(0, text.size() - 61) + ",1e999]" + std::string(60, '}');
  try {
    parse_json(bad, "f.json");
    FAIL_CHECK("accepted");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CHECK(message.size() < 400);
    CHECK(message.find("[20000]: number 1e999 out of range") != std::string::npos);
  }
}

TEST_CASE("json_field: messages quote user text escaped and shortened") {
  const std::string key = std::string("bad\0key", 7) + std::string(100000, 'x');
  const nlohmann::json document = {{key, 1}};
  const JsonField root(document, "", "f.json");
  try {
    root.check_keys({"linkage"});
    FAIL_CHECK("accepted");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CHECK(message.rfind("f.json: unknown key \"bad\\0key", 0) == 0);
    CHECK(message.size() < 400);
  }
  const nlohmann::json value = {{"s", std::string("line\nbreak") + std::string(1000, 'y')}};
  const JsonField s = JsonField(value, "", "f.json").require("s");
  CHECK_THROWS_WITH_AS(s.number(), doctest::Contains("got a string (\"line\\nbreak"), InputError);
  try {
    s.choice(std::vector<std::pair<int, std::string>>{{1, "one"}});
    FAIL_CHECK("accepted");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
    CHECK(std::string(e.what()).size() < 200);
  }
}

}  // namespace xshell::test
