#include "obj_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <string_view>

#include "input_error.hpp"
#include "input_file.hpp"
#include "linkage/bounding_box.hpp"

namespace xshell {
namespace {

// ---------------------------------------------------------------------------
// Messages

std::string where(const std::string& name, int line) {
  return name + ":" + std::to_string(line) + ": ";
}

[[noreturn]] void fail(const std::string& name, int line, const std::string& what) {
  throw InputError(where(name, line) + what);
}

// A token as it appears in a message: quoted, escaped, shortened if long.
std::string quoted(std::string_view token) { return "'" + printable(token, 40) + "'"; }

std::string vertex_name(int v) { return "vertex " + std::to_string(v) + " (0-based)"; }

std::string vertex_name(int v, int line) {
  return "vertex " + std::to_string(v) + " (0-based, line " + std::to_string(line) + ")";
}

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::string position(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(10);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// ---------------------------------------------------------------------------
// Tokens

std::vector<std::string_view> split(std::string_view text) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    std::size_t j = i;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j > i) tokens.push_back(text.substr(i, j - i));
    i = j;
  }
  return tokens;
}

// Whole-token conversions; from_chars is locale-independent. A leading '+'
// (which from_chars does not take) is allowed as in C's strtod.
template <typename T>
std::from_chars_result parse_number(std::string_view token, T& value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  auto result = std::from_chars(token.data(), end, value);
  if (result.ec == std::errc() && result.ptr != end) result.ec = std::errc::invalid_argument;
  return result;
}

// ---------------------------------------------------------------------------
// Statements

// What a file describes: a linkage (vertices and 'l' lines) or a surface
// (vertices and 'f' lines).
enum class ObjContent { Lines, Faces };

class ObjParser {
 public:
  ObjParser(const std::string& name, ObjContent content) : name_(name), content_(content) {}

  void parse_line(std::string_view text, int line) {
    text = text.substr(0, text.find('#'));
    const auto tokens = split(text);
    if (tokens.empty()) return;
    const std::string_view keyword = tokens[0];
    if (keyword == "v") return vertex(tokens, line);
    if (keyword == "l" && content_ == ObjContent::Lines) return polyline(tokens, line);
    if (keyword == "f" && content_ == ObjContent::Faces) return face(tokens, line);
    static const char* const kSkipped[] = {"o", "g", "s", "vt", "vn", "mtllib", "usemtl"};
    for (const char* skipped : kSkipped)
      if (keyword == skipped) return;
    if (keyword == "f")
      fail(name_, line,
           "faces ('f') are not allowed: a linkage is a line mesh of vertices ('v') and "
           "rod segments ('l')");
    if (content_ == ObjContent::Faces)
      fail(name_, line,
           "unknown statement " + quoted(keyword) +
               "; a surface file has 'v' and 'f' lines (comments and o, g, s, vt, vn, mtllib, "
               "usemtl lines are skipped)");
    fail(name_, line,
         "unknown statement " + quoted(keyword) +
             "; a linkage file has 'v' and 'l' lines (comments and o, g, s, vt, vn, mtllib, "
             "usemtl lines are skipped)");
  }

  // Checks the indices against the final vertex count (a positive index may
  // name a vertex defined further down).
  ObjLineGraph finish() {
    for (std::size_t e = 0; e < out_.graph.edges.size(); ++e)
      for (int v : out_.graph.edges[e]) check_defined(v, out_.edge_lines[e]);
    return std::move(out_);
  }
  ObjSurface finish_surface() {
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      for (int v : triangles_[t]) check_defined(v, triangle_lines_[t]);
    return {std::move(out_.graph.vertices), std::move(triangles_)};
  }

 private:
  void vertex(const std::vector<std::string_view>& tokens, int line) {
    const std::size_t count = tokens.size() - 1;
    if (count < 3)
      fail(name_, line,
           "vertex has " + std::to_string(count) + " coordinate(s); 'v x y z' needs three");
    if (count > 4)
      fail(name_, line,
           "vertex has " + std::to_string(count) +
               " coordinates; 'v x y z' takes three (and an optional w)");
    double c[4] = {0, 0, 0, 1};
    for (std::size_t i = 0; i < count; ++i) {
      const std::string what = "coordinate " + quoted(tokens[i + 1]);
      const auto result = parse_number(tokens[i + 1], c[i]);
      if (result.ec == std::errc::result_out_of_range)
        fail(name_, line, what + " is out of the range of double-precision numbers");
      if (result.ec != std::errc()) fail(name_, line, what + " is not a number");
      if (!std::isfinite(c[i])) fail(name_, line, what + " is not a finite number");
      if (i < 3 && std::abs(c[i]) > kMaxCoordinate)
        fail(name_, line,
             what + " is outside the supported range: coordinates are at most " +
                 number(kMaxCoordinate) + " in absolute value (choose a larger length unit)");
    }
    if (content_ == ObjContent::Lines &&
        out_.graph.vertices.size() > static_cast<std::size_t>(kMaxLinkageSegments))
      fail(name_, line,
           "more than " + std::to_string(kMaxLinkageSegments + 1) +
               " vertices: a linkage may have at most " + std::to_string(kMaxLinkageSegments) +
               " segments (" + std::to_string(kMaxRodEdges) + " rod edges at " +
               std::to_string(kMinSubdivisions) + " subdivisions), hence at most " +
               std::to_string(kMaxLinkageSegments + 1) + " vertices in use");
    out_.graph.vertices.emplace_back(c[0], c[1], c[2]);
    out_.vertex_lines.push_back(line);
  }

  void polyline(const std::vector<std::string_view>& tokens, int line) {
    if (tokens.size() < 3) fail(name_, line, "'l' needs at least two vertex indices ('l i j')");
    int previous = -1;
    for (std::size_t i = 1; i < tokens.size(); ++i) {
      const int v = index(tokens[i], line);
      if (previous >= 0) {
        if (out_.graph.edges.size() >= static_cast<std::size_t>(kMaxLinkageSegments))
          fail(name_, line,
               "more than " + std::to_string(kMaxLinkageSegments) +
                   " rod segments: a run may have at most " + std::to_string(kMaxRodEdges) +
                   " rod edges, and a segment has at least " + std::to_string(kMinSubdivisions));
        out_.graph.edges.push_back({previous, v});
        out_.edge_lines.push_back(line);
      }
      previous = v;
    }
  }

  // A polygon "f i j k ...", split into the triangles (i, j, k), (i, k, l), ...
  void face(const std::vector<std::string_view>& tokens, int line) {
    if (tokens.size() < 4) fail(name_, line, "'f' needs at least three vertex indices ('f i j k')");
    const int first = index(tokens[1], line);
    int previous = index(tokens[2], line);
    for (std::size_t i = 3; i < tokens.size(); ++i) {
      const int v = index(tokens[i], line);
      triangles_.push_back({first, previous, v});
      triangle_lines_.push_back(line);
      previous = v;
    }
  }

  void check_defined(int v, int line) const {
    const int n = static_cast<int>(out_.graph.vertices.size());
    if (v >= n)
      fail(name_, line,
           "vertex index " + std::to_string(v + 1) + " is out of range: the file defines " +
               std::to_string(n) + " vertices");
  }

  // 0-based index of one "i", "i/t", "i//n" or "i/t/n" entry.
  int index(std::string_view token, int line) const {
    const std::string_view text = token.substr(0, token.find('/'));
    long long value = 0;
    const auto result = parse_number(text, value);
    if (result.ec == std::errc::result_out_of_range)
      fail(name_, line, "vertex index " + quoted(token) + " is out of range");
    if (result.ec != std::errc())
      fail(name_, line, "vertex index " + quoted(token) + " is not an integer");
    const long long defined = static_cast<long long>(out_.graph.vertices.size());
    if (value == 0) fail(name_, line, "vertex index 0 is invalid: OBJ indices start at 1");
    if (value < 0) {
      if (value < -defined)
        fail(name_, line,
             "relative vertex index " + std::to_string(value) +
                 " reaches before the first vertex (" + std::to_string(defined) +
                 " defined so far)");
      return static_cast<int>(defined + value);
    }
    if (value > std::numeric_limits<int>::max())
      fail(name_, line, "vertex index " + quoted(token) + " is out of range");
    return static_cast<int>(value - 1);
  }

  const std::string& name_;
  ObjContent content_;
  ObjLineGraph out_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<int> triangle_lines_;
};

// ---------------------------------------------------------------------------
// Graph checks, in the order a user would fix them.

void check_self_loops(const ObjLineGraph& g, const std::string& name) {
  for (std::size_t e = 0; e < g.graph.edges.size(); ++e) {
    const auto [a, b] = g.graph.edges[e];
    if (a == b)
      fail(name, g.edge_lines[e],
           "self-loop: the edge joins " + vertex_name(a, g.vertex_lines[a]) + " to itself");
  }
}

void check_duplicate_edges(const ObjLineGraph& g, const std::string& name) {
  std::map<std::pair<int, int>, std::size_t> first;
  for (std::size_t e = 0; e < g.graph.edges.size(); ++e) {
    const auto [a, b] = g.graph.edges[e];
    const auto [it, inserted] = first.emplace(std::minmax(a, b), e);
    if (inserted) continue;
    const int other = g.edge_lines[it->second];
    fail(name, g.edge_lines[e],
         "duplicate edge between vertices " + std::to_string(a) + " and " + std::to_string(b) +
             " (0-based): " +
             (other == g.edge_lines[e] ? std::string("already defined earlier on this line")
                                       : "already defined at line " + std::to_string(other)));
  }
}

void check_edge_lengths(const ObjLineGraph& g, double tolerance, const std::string& name) {
  const auto& x = g.graph.vertices;
  for (std::size_t e = 0; e < g.graph.edges.size(); ++e) {
    const auto [a, b] = g.graph.edges[e];
    if ((x[a] - x[b]).norm() > tolerance) continue;
    fail(name, g.edge_lines[e],
         "zero-length edge: vertices " + std::to_string(a) + " and " + std::to_string(b) +
             " (0-based; lines " + std::to_string(g.vertex_lines[a]) + " and " +
             std::to_string(g.vertex_lines[b]) + ") are both at " + position(x[a]));
  }
}

// Sort-and-sweep along a direction d: only vertices whose projections on d
// differ by at most the tolerance are compared, so large files stay fast. d
// is oblique so that the rows and columns of a grid do not share projections.
// Reports the pair whose later vertex comes first in the file.
void check_coincident_vertices(const ObjLineGraph& g, double tolerance, const std::string& name) {
  const auto& x = g.graph.vertices;
  const Eigen::Vector3d d = Eigen::Vector3d(1, 0.6180339887, 0.3819660113).normalized();
  std::vector<double> key(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) key[i] = d.dot(x[i]);
  std::vector<int> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  std::pair<int, int> worst{-1, -1};  // (later, earlier)
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && key[order[j]] - key[order[i]] <= tolerance;
         ++j) {
      if ((x[order[i]] - x[order[j]]).norm() > tolerance) continue;
      const auto pair = std::make_pair(std::max(order[i], order[j]), std::min(order[i], order[j]));
      if (worst.first < 0 || pair < worst) worst = pair;
    }
  if (worst.first < 0) return;
  const auto [later, earlier] = worst;
  fail(name, g.vertex_lines[later],
       vertex_name(later) + " coincides with " + vertex_name(earlier, g.vertex_lines[earlier]) +
           " at " + position(x[later]) + "; merge them or move one");
}

void check_valences(const ObjLineGraph& g, const std::string& name) {
  const std::vector<int> valence = valences(g.graph);
  for (std::size_t v = 0; v < valence.size(); ++v) {
    const int line = g.vertex_lines[v];
    if (valence[v] == 0)
      fail(name, line, vertex_name(static_cast<int>(v)) + " is isolated: no 'l' line uses it");
    if (valence[v] > 4)
      fail(name, line,
           vertex_name(static_cast<int>(v)) + " has valence " + std::to_string(valence[v]) +
               "; a scissor joint joins at most 4 rod segments");
  }
}

// Labels connected components by union-find and reports the first vertex
// outside the component of vertex 0.
void check_connected(const ObjLineGraph& g, const std::string& name) {
  std::vector<int> parent(g.graph.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& [a, b] : g.graph.edges) parent[root(a)] = root(b);
  int components = 0, stray = -1;
  for (int v = 0; v < static_cast<int>(parent.size()); ++v) {
    if (root(v) == v) ++components;
    if (stray < 0 && root(v) != root(0)) stray = v;
  }
  if (stray < 0) return;
  fail(name, g.vertex_lines[stray],
       "the linkage is not connected (" + std::to_string(components) + " components): " +
           vertex_name(stray) + " cannot be reached from " + vertex_name(0, g.vertex_lines[0]));
}

void check_graph(const ObjLineGraph& g, const std::string& name) {
  if (g.graph.edges.empty())
    throw InputError(name + ": no rod segments: a linkage needs at least one 'l' line");
  check_self_loops(g, name);
  check_duplicate_edges(g, name);
  // stableNorm: no underflow for a linkage 1e-300 across.
  const double size = bounding_box(g.graph.vertices).diagonal().stableNorm();
  if (size < kMinLinkageSize)
    throw InputError(name + ": the linkage measures " + number(size) +
                     " across (its bounding-box diagonal); at least " + number(kMinLinkageSize) +
                     " is supported: choose a smaller length unit");
  const double tolerance = 1e-12 * size;
  check_edge_lengths(g, tolerance, name);
  check_coincident_vertices(g, tolerance, name);
  check_valences(g, name);
  check_connected(g, name);
}

// Feeds every line of `text` to `parser`.
void parse_lines(std::string_view text, ObjParser& parser) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte order mark
  int line = 0;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find_first_of("\r\n", begin);
    if (end == std::string_view::npos) end = text.size();
    parser.parse_line(text.substr(begin, end - begin), ++line);
    // A line ends with LF, CRLF or CR alone.
    begin = end + (text.substr(end, 2) == "\r\n" ? 2 : 1);
  }
}

}  // namespace

ObjLineGraph parse_obj_text(std::string_view text, const std::string& name) {
  ObjParser parser(name, ObjContent::Lines);
  parse_lines(text, parser);
  ObjLineGraph g = parser.finish();
  check_graph(g, name);
  return g;
}

ObjSurface parse_obj_surface_text(std::string_view text, const std::string& name) {
  ObjParser parser(name, ObjContent::Faces);
  parse_lines(text, parser);
  ObjSurface surface = parser.finish_surface();
  if (surface.triangles.empty())
    throw InputError(name + ": no faces: a surface needs at least one 'f' line");
  return surface;
}

ObjSurface read_obj_surface(const std::string& path) {
  const std::string shown = printable(path);
  const std::string text =
      read_input_file(path, kSurfaceFile, "cannot open surface file '" + shown + "'");
  return parse_obj_surface_text(text, shown);
}

ObjLineGraph parse_obj_with_lines(std::istream& in, const std::string& name) {
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxLinkageFileBytes)
      throw InputError(name + ": more than " + std::to_string(kMaxLinkageFileBytes) +
                       " bytes; a linkage file may have at most that many");
  }
  if (in.bad()) throw InputError(name + ": read error");
  return parse_obj_text(text, name);
}

LineGraph parse_obj(std::istream& in, const std::string& name) {
  return parse_obj_with_lines(in, name).graph;
}

ObjLineGraph read_obj_with_lines(const std::string& path) {
  const std::string shown = printable(path);  // the name as messages quote it
  const std::string text =
      read_input_file(path, kLinkageFile, "cannot open linkage file '" + shown + "'");
  return parse_obj_text(text, shown);
}

LineGraph read_obj(const std::string& path) { return read_obj_with_lines(path).graph; }

}  // namespace xshell
