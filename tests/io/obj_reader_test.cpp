#include "io/obj_reader.hpp"

#include <doctest/doctest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <sstream>

#include "io/input_error.hpp"
#include "io/input_file.hpp"
#include "scratch_directory.hpp"
#include "skip.hpp"

namespace xshell::test {
namespace {

ObjLineGraph parse(const std::string& text) {
  std::istringstream in(text);
  return parse_obj_with_lines(in, "t.obj");
}

// The message of the InputError that `text` raises, or "" (with a failed
// check) when it is accepted or raises anything else.
std::string rejection(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  } catch (...) {
    FAIL_CHECK("not an InputError");
    return "";
  }
  FAIL_CHECK("accepted: " << text);
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Checks that the message starts with "t.obj:LINE: " and contains every key
// word; each part is a separate check so that a failure names it.
void check_message(const std::string& message, int line, std::vector<std::string> words) {
  INFO("message: " << message);
  CHECK(message.rfind("t.obj:" + std::to_string(line) + ": ", 0) == 0);
  for (const auto& w : words) CHECK_MESSAGE(contains(message, w), "missing: " << w);
}

const char* const kX =  // one X joint (vertex 2), four free ends
    "v -1 -1 0\nv 1 1 0\nv 0 0 0\nv 1 -1 0\nv -1 1 0\n";

}  // namespace

// ---------------------------------------------------------------------------
// Accepted input

TEST_CASE("obj: skipped statements, comments, CRLF and the w component") {
  const auto g = parse(
      "\xEF\xBB\xBF# a comment after a UTF-8 byte order mark\r\n"
      "mtllib x.mtl\r\n"
      "o linkage\r\n"
      "g group\r\n"
      "\r\n"
      "v -1 -1 0 1\r\n"
      "v 1 1 0   # trailing comment\r\n"
      "vt 0 0\r\n"
      "vn 0 0 1\r\n"
      "v +0 0 0\r\n"
      "usemtl m\r\n"
      "s off\r\n"
      "\tl 1 3\r\n"
      "l 3 2\r\n");
  REQUIRE(g.graph.vertices.size() == 3);
  REQUIRE(g.graph.edges.size() == 2);
  CHECK(g.graph.vertices[0] == Eigen::Vector3d(-1, -1, 0));
  CHECK(g.graph.edges[0] == std::array<int, 2>{0, 2});
  CHECK(g.graph.edges[1] == std::array<int, 2>{2, 1});
  CHECK(g.vertex_lines == std::vector<int>{6, 7, 10});
  CHECK(g.edge_lines == std::vector<int>{13, 14});
}

TEST_CASE("obj: a polyline becomes consecutive edges") {
  const auto g = parse(std::string(kX) + "l 1 3 2\nl 4 3 5\n");
  CHECK(g.graph.edges == std::vector<std::array<int, 2>>{{0, 2}, {2, 1}, {3, 2}, {2, 4}});
  CHECK(g.edge_lines == std::vector<int>{6, 6, 7, 7});
  CHECK(valences(g.graph) == std::vector<int>{1, 1, 4, 1, 1});
}

TEST_CASE("obj: negative indices count back from the last vertex so far") {
  const auto g = parse(
      "v 0 0 0\nv 1 0 0\nl -2 -1\n"  // 0-1
      "v 2 0 0\nl -2 -1\n"           // 1-2
      "v 3 0 0\nl -1 1\n");          // 3-0
  CHECK(g.graph.edges == std::vector<std::array<int, 2>>{{0, 1}, {1, 2}, {3, 0}});
}

TEST_CASE("obj: i/t, i//n and i/t/n entries use the vertex index") {
  const auto g = parse("v 0 0 0\nv 1 0 0\nv 2 0 0\nl 1/1 2//3 3/2/1\n");
  CHECK(g.graph.edges == std::vector<std::array<int, 2>>{{0, 1}, {1, 2}});
}

TEST_CASE("obj: a positive index may name a vertex defined further down") {
  const auto g = parse("l 1 2\nv 0 0 0\nv 1 0 0\n");
  CHECK(g.graph.edges == std::vector<std::array<int, 2>>{{0, 1}});
}

TEST_CASE("obj: read_obj reads a file and reports one that cannot be opened") {
  const ScratchDirectory dir("obj-reader");
  const auto path = dir / "x.obj";
  std::ofstream(path) << kX << "l 1 3\nl 3 2\nl 4 3\nl 3 5\n";
  const LineGraph g = read_obj(path.string());
  CHECK(g.vertices.size() == 5);
  CHECK(g.edges.size() == 4);
  std::filesystem::remove(path);
  const std::string expected = "cannot open linkage file '" + path.string() + "'";
  CHECK_THROWS_WITH_AS(read_obj(path.string()), doctest::Contains(expected.c_str()), InputError);
}

// ---------------------------------------------------------------------------
// Rejected syntax

TEST_CASE("obj: rejects an unparsable coordinate") {
  check_message(rejection("v 0 0 0\nv 1 x 0\nl 1 2\n"), 2, {"'x'", "not a number"});
  check_message(rejection("v 0 0 0\nv 1 2.5.1 0\nl 1 2\n"), 2, {"'2.5.1'", "not a number"});
}

TEST_CASE("obj: rejects non-finite coordinates") {
  check_message(rejection("v 0 0 0\nv nan 0 0\nl 1 2\n"), 2, {"'nan'", "not a finite number"});
  check_message(rejection("v 0 0 0\nv 0 -inf 0\nl 1 2\n"), 2, {"'-inf'", "not a finite"});
  check_message(rejection("v 0 0 0\nv 0 0 1e999\nl 1 2\n"), 2, {"'1e999'", "out of the range"});
}

TEST_CASE("obj: rejects too few and too many coordinates") {
  check_message(rejection("v 0 0 0\nv 1 0\nl 1 2\n"), 2, {"2 coordinate", "needs three"});
  check_message(rejection("v 0 0 0 1 2\n"), 1, {"5 coordinates"});
}

TEST_CASE("obj: rejects index 0") {
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 0 1\n"), 3, {"index 0", "start at 1"});
}

TEST_CASE("obj: rejects an index out of range") {
  check_message(rejection("v 0 0 0\nv 1 0 0\n\nl 1 3\n"), 4,
                {"vertex index 3", "out of range", "defines 2 vertices"});
  check_message(rejection("v 0 0 0\nv 1 0 0\nl -3 1\n"), 3,
                {"relative vertex index -3", "2 defined so far"});
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 99999999999\n"), 3,
                {"'99999999999'", "out of range"});
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 -9223372036854775808\n"), 3,
                {"relative vertex index -9223372036854775808"});
}

TEST_CASE("obj: rejects an index that is not an integer") {
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 2.0\n"), 3, {"'2.0'", "not an integer"});
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 /2\n"), 3, {"'/2'", "not an integer"});
}

TEST_CASE("obj: rejects an 'l' with one index") {
  check_message(rejection("v 0 0 0\nl 1\n"), 2, {"at least two vertex indices"});
}

TEST_CASE("obj: rejects faces") {
  check_message(rejection("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), 4, {"faces ('f')"});
}

TEST_CASE("obj: rejects an unknown statement, naming it") {
  check_message(rejection("v 0 0 0\np 1\n"), 2, {"unknown statement 'p'"});
  check_message(rejection("vp 0.5\n"), 1, {"unknown statement 'vp'"});
}

// ---------------------------------------------------------------------------
// Rejected graphs

TEST_CASE("obj: rejects a self-loop") {
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 2\nl 2 2\n"), 4,
                {"self-loop", "vertex 1 (0-based, line 2)"});
}

TEST_CASE("obj: rejects a duplicate edge in either orientation") {
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 2\nl 2 1\n"), 4,
                {"duplicate edge", "vertices 1 and 0", "line 3"});
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 2\n\nl 1 2\n"), 5, {"duplicate edge", "line 3"});
  check_message(rejection("v 0 0 0\nv 1 0 0\nl 1 2 1\n"), 3, {"duplicate edge", "this line"});
}

TEST_CASE("obj: rejects a zero-length edge") {
  check_message(rejection("v 0 0 0\nv 1 0 0\nv 1 0 0\nl 1 2\nl 2 3\n"), 5,
                {"zero-length edge", "vertices 1 and 2 (0-based; lines 2 and 3)"});
}

TEST_CASE("obj: rejects coincident vertices, naming both lines") {
  // Vertices 1 and 3 coincide but are not joined by an edge.
  const std::string text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 0 0\nl 1 2\nl 2 3\nl 3 4\n";
  check_message(rejection(text), 4,
                {"vertex 3 (0-based) coincides with vertex 1 (0-based, line 2)", "(1, 0, 0)"});
  // Within 1e-12 of the bounding-box diagonal (here 2) is the same position...
  const std::string close = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 1e-12 0\nl 1 2\nl 2 3\nl 3 4\n";
  check_message(rejection(close), 4, {"coincides"});
  // ...but farther is not.
  const auto g = parse("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 1e-11 0\nl 1 2\nl 2 3\nl 3 4\n");
  CHECK(g.graph.edges.size() == 3);
}

TEST_CASE("obj: rejects an isolated vertex") {
  check_message(rejection("v 0 0 0\nv 1 0 0\nv 5 5 5\nl 1 2\n"), 3,
                {"vertex 2 (0-based)", "isolated"});
}

TEST_CASE("obj: rejects a vertex of valence above 4") {
  const std::string star =
      "v 0 0 0\nv 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
      "l 1 2\nl 1 3\nl 1 4\nl 1 5\nl 1 6\n";
  check_message(rejection(star), 1, {"vertex 0 (0-based)", "valence 5", "at most 4"});
}

TEST_CASE("obj: rejects a disconnected graph, naming a vertex of a second component") {
  check_message(
      rejection("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nl 1 2\nl 3 4\n"), 3,
      {"not connected", "2 components", "vertex 2 (0-based)", "vertex 0 (0-based, line 1)"});
}

TEST_CASE("obj: rejects a file without edges") {
  for (const std::string text : {"", "# empty\n", "v 0 0 0\nv 1 0 0\n"}) {
    const std::string message = rejection(text);
    CHECK(message.rfind("t.obj: ", 0) == 0);
    CHECK(contains(message, "no rod segments"));
  }
}

// ---------------------------------------------------------------------------
// Line endings, limits and messages

TEST_CASE("obj: lines end with LF or CRLF or CR alone") {
  const std::string lines[] = {"v 0 0 0", "v 1 0 0", "v 1 1 0", "# a comment", "l 1 2", "l 2 3"};
  int checked = 0;
  for (const std::string end : {"\n", "\r\n", "\r"}) {
    std::string text;
    for (const auto& line : lines) text += line + end;
    CAPTURE(text);
    const auto g = parse(text);
    CHECK(g.graph.vertices.size() == 3);
    CHECK(g.graph.edges.size() == 2);
    CHECK(g.edge_lines == std::vector<int>{5, 6});
    ++checked;
  }
  CHECK(checked == 3);
  // Mixed, and errors name the right line.
  check_message(rejection("v 0 0 0\rv 1 0 0\r\nv 1 x 0\nl 1 2\r"), 3, {"'x'"});
}

TEST_CASE("obj: coordinates beyond 1e12 or a linkage smaller than 1e-6 are refused") {
  check_message(rejection("v 0 0 0\nv 1.5e12 0 0\nl 1 2\n"), 2,
                {"coordinate '1.5e12' is outside the supported range", "1e+12"});
  check_message(rejection("v -5e299 -3.75e299 0\nv 1 0 0\nl 1 2\n"), 1,
                {"coordinate '-5e299' is outside"});
  CHECK_NOTHROW(parse("v 0 0 0\nv 1e12 -1e12 0\nl 1 2\n"));
  // Points 1e-300 apart: their distance squared underflows to zero, which
  // read as a zero-length edge between two distinct points.
  const std::string tiny = rejection("v 1e-300 0 0\nv 2e-300 0 0\nl 1 2\n");
  CHECK(tiny.rfind("t.obj: the linkage measures 1e-300 across", 0) == 0);
  CHECK(contains(tiny, "at least 1e-06"));
  CHECK_NOTHROW(parse("v 0 0 0\nv 1e-6 0 0\nl 1 2\n"));
  // A tiny coordinate in a linkage of normal size is fine (round-off zeros).
  CHECK_NOTHROW(parse("v 6.1e-17 0 0\nv 1 0 0\nl 1 2\n"));
}

TEST_CASE("obj: more segments or vertices than a run may have are refused while reading") {
  std::string text = "v 0 0 0\nv 1 0 0\nl";
  for (long i = 0; i <= kMaxLinkageSegments + 1; ++i) text += i % 2 ? " 2" : " 1";
  check_message(rejection(text + "\n"), 3,
                {"more than " + std::to_string(kMaxLinkageSegments) + " rod segments"});
  std::string vertices;
  for (long i = 0; i < kMaxLinkageSegments + 2; ++i) vertices += "v 0 0 0\n";
  check_message(rejection(vertices), static_cast<int>(kMaxLinkageSegments + 2),
                {"more than " + std::to_string(kMaxLinkageSegments + 1) + " vertices"});
}

TEST_CASE("obj: a NUL byte or a long token is quoted escaped and short") {
  const std::string message = rejection(std::string("v 0 0 0\nv 1 0\0 0\nl 1 2\n", 23));
  check_message(message, 2, {"coordinate '0\\0' is not a number"});
  CHECK(message.find('\0') == std::string::npos);
  const std::string long_token = rejection("v 0 0 0\nv 1 " + std::string(100000, '9') + "x 0\n");
  CHECK(long_token.size() < 200);
  check_message(long_token, 2, {"...", "9x'"});
}

TEST_CASE("obj: read_obj refuses a FIFO or a device or an oversized file at once") {
  namespace fs = std::filesystem;
  const ScratchDirectory scratch("obj-kinds");
  const fs::path& dir = scratch.path();
  REQUIRE(::mkfifo((dir / "fifo.obj").c_str(), 0600) == 0);
  auto reading = std::async(std::launch::async, [&]() -> std::string {
    try {
      read_obj((dir / "fifo.obj").string());
    } catch (const InputError& e) {
      return e.what();
    }
    return "(read)";
  });
  if (reading.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    FAIL_CHECK("reading a FIFO blocked");
    std::ofstream(dir / "fifo.obj") << "";  // the writer the reader waits for
  }
  CHECK(reading.get() == "cannot open linkage file '" + (dir / "fifo.obj").string() +
                             "': it is a FIFO (named pipe), not a regular file");
  CHECK_THROWS_WITH_AS(read_obj("/dev/zero"),
                       "cannot open linkage file '/dev/zero': it is a device, not a regular file",
                       InputError);
  { std::ofstream(dir / "huge.obj") << ""; }
  fs::resize_file(dir / "huge.obj", std::uintmax_t{257} << 20);  // sparse: no disk
  CHECK_THROWS_WITH_AS(read_obj((dir / "huge.obj").string()),
                       doctest::Contains("a linkage file may have at most 268435456"), InputError);
  // A path quoted in full would make a message as long as the path.
  const std::string long_path = "/" + std::string(100000, 'd') + "/grid.obj";
  try {
    read_obj(long_path);
    FAIL_CHECK("accepted");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).size() < 300);
    CHECK(contains(e.what(), "/grid.obj': File name too long"));
  }
}

// ---------------------------------------------------------------------------
// The reference implementation's linkages (outside the repository)

TEST_CASE("obj: every shared linkage loads with the documented counts") {
  namespace fs = std::filesystem;
  const fs::path folder = XSHELL_SHARED_DATA_DIR;
  if (!fs::is_directory(folder)) XSHELL_SKIP(folder.string() + " is absent");
  struct Expected {
    int vertices, segments;
    std::map<int, int> valences;  // valence -> number of vertices
  };
  // From README.txt in that folder.
  const std::map<std::string, Expected> table = {
      {"single_linkage.obj", {5, 4, {{1, 4}, {4, 1}}}},
      {"fish_linkage.obj", {6, 6, {{1, 2}, {2, 3}, {4, 1}}}},
      {"hyperboloid_open.obj", {33, 52, {{2, 13}, {3, 2}, {4, 18}}}},
      {"uniform_linkage.obj", {105, 180, {{1, 4}, {2, 24}, {4, 77}}}},
      {"sphere_open.obj", {140, 248, {{1, 2}, {2, 28}, {3, 2}, {4, 108}}}},
      {"manta_ray_5ca2f7ab.obj", {169, 312, {{2, 4}, {3, 44}, {4, 121}}}},
      {"darth_vader_fig5_1693d9a2.obj", {157, 288, {{2, 10}, {3, 32}, {4, 115}}}},
      {"scary_face_8f39dd30.obj", {368, 664, {{2, 66}, {3, 12}, {4, 290}}}},
      {"hourglass_912c32dc.obj", {805, 1532, {{2, 76}, {3, 4}, {4, 725}}}},
      {"large_6d35a972.obj", {1371, 2668, {{2, 50}, {3, 48}, {4, 1273}}}},
  };
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".obj") continue;
    const std::string file = entry.path().filename().string();
    INFO("file: " << file);
    const auto start = std::chrono::steady_clock::now();
    LineGraph g;
    REQUIRE_NOTHROW(g = read_obj(entry.path().string()));
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    CHECK(elapsed.count() < 1.0);
    const auto row = table.find(file);
    REQUIRE_MESSAGE(row != table.end(), "not in the README table");
    CHECK(static_cast<int>(g.vertices.size()) == row->second.vertices);
    CHECK(static_cast<int>(g.edges.size()) == row->second.segments);
    std::map<int, int> histogram;
    for (int v : valences(g)) ++histogram[v];
    CHECK(histogram == row->second.valences);
    ++checked;
  }
  CHECK(checked == 10);
}

}  // namespace xshell::test
