#include "state_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.hpp"
#include "input_error.hpp"
#include "input_file.hpp"
#include "json_field.hpp"
#include "linkage/bounding_box.hpp"

namespace xshell {

namespace {
using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

const char* rest_name(RestShape r) { return r == RestShape::Input ? "input" : "straight"; }

// "joint_kind": the parametrization of every joint's "params" and
// "reference_frame" (joint.hpp); absent in files written before edge-vector
// joints existed, which are all rotation joints. A state of the other kind is
// converted on restore (RodLinkage::restore).
const char* joint_kind_name(JointKind k) {
  return k == JointKind::Rotation ? "rotation" : "edge_vectors";
}

JointKind joint_kind(const json& doc) {
  const std::string name = doc.value("joint_kind", "rotation");
  if (name == "rotation") return JointKind::Rotation;
  if (name == "edge_vectors") return JointKind::EdgeVectors;
  throw std::invalid_argument("unknown \"joint_kind\": \"" + name + "\"");
}

// "clamped_ends" only where the linkage clamps some free end (which changes
// its end edges' layout), so that states of unclamped linkages written before
// clamps were centred on their vertices still match.
json fingerprint(const RodLinkage& linkage) {
  json out = {{"vertices", linkage.graph().vertices.size()},
              {"edges", linkage.graph().edges.size()},
              {"subdivisions", linkage.options().subdivisions},
              {"rest_shape", rest_name(linkage.options().rest_shape)},
              {"graph_hash", graph_hash(linkage.graph())}};
  if (!linkage.options().clamped_ends.empty()) out["clamped_ends"] = linkage.options().clamped_ends;
  if (!linkage.options().segment_rest_lengths.empty())
    out["rest_lengths"] = linkage.options().segment_rest_lengths;
  return out;
}

// A fingerprint without its rest lengths (a copy).
json without_rest_lengths(json fingerprint) {
  if (fingerprint.is_object()) fingerprint.erase("rest_lengths");
  return fingerprint;
}

// How the rest lengths of two fingerprints that agree otherwise differ.
std::string rest_lengths_difference(const json& saved, const json& expected) {
  const auto lengths = [](const json& f) {
    const auto it = f.find("rest_lengths");
    return it == f.end() ? json::array() : *it;
  };
  const json a = lengths(saved), b = lengths(expected);
  std::string what;
  const auto number = [](const json& l) { return l.is_number(); };
  // Written only when given, and then as a non-empty array of numbers.
  if (saved.contains("rest_lengths") &&
      (!a.is_array() || a.empty() || !std::all_of(a.begin(), a.end(), number)))
    what = "the state's fingerprint has malformed \"rest_lengths\"";
  else if (a.empty())
    what = "the state was saved with the drawing's rest lengths, this run gives \"rest_lengths\"";
  else if (b.empty())
    what = "the state was saved with \"rest_lengths\", this run has the drawing's rest lengths";
  else if (a.size() != b.size())
    what = "the state was saved with " + std::to_string(a.size()) +
           " \"rest_lengths\", this run "
           "gives " +
           std::to_string(b.size());
  else
    for (std::size_t s = 0; s < a.size() && what.empty(); ++s)
      if (a[s] != b[s])
        what = "the state was saved with other \"rest_lengths\" (segment " + std::to_string(s) +
               ": " + printable(a[s].dump()) + " in the state, " + b[s].dump() + " in this run)";
  return what + "; give the rest lengths it was saved with, or start without --init";
}
}  // namespace

std::string graph_hash(const LineGraph& graph) {
  // FNV-1a over the edges and the coordinates (printed exactly).
  std::uint64_t h = 1469598103934665603ull;
  auto feed = [&](const std::string& s) {
    for (unsigned char c : s) {
      h ^= c;
      h *= 1099511628211ull;
    }
  };
  char buffer[64];
  for (const auto& v : graph.vertices)
    for (int c = 0; c < 3; ++c) {
      std::snprintf(buffer, sizeof buffer, "%.17g,", v[c]);
      feed(buffer);
    }
  for (const auto& e : graph.edges) feed(std::to_string(e[0]) + "-" + std::to_string(e[1]) + ";");
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

std::string state_text(const RodLinkage& linkage, const Eigen::Vector3d& origin) {
  const LinkageState state = linkage.state();
  json segments = json::array();
  for (const SegmentState& s : state.segments) {
    json nodes = json::array(), frames = json::array();
    for (const auto& x : s.nodes) nodes.push_back(vec(x));
    for (const auto& f : s.source_frames)
      frames.push_back({{"tangent", vec(f.tangent)}, {"d1", vec(f.d1)}});
    segments.push_back({{"nodes", nodes},
                        {"thetas", s.thetas},
                        {"source_frames", frames},
                        {"twist_hints", s.twist_hints}});
  }
  json joints = json::array();
  for (size_t j = 0; j < state.joints.size(); ++j) {
    const JointState& js = state.joints[j];
    json frame = json::array();
    for (int c = 0; c < 3; ++c) frame.push_back(vec(js.reference_frame.col(c)));
    joints.push_back({{"vertex", linkage.topology().joints[j].vertex},
                      {"params", std::vector<double>(js.params.data(), js.params.data() + 9)},
                      {"reference_frame", frame}});
  }
  const json doc = {{"format", "xshell-state"},
                    {"version", 1},
                    {"fingerprint", fingerprint(linkage)},
                    {"origin", vec(origin)},
                    {"joint_kind", joint_kind_name(linkage.options().joint_kind)},
                    {"segments", segments},
                    {"joints", joints}};
  return doc.dump() + "\n";
}

void write_state(const std::string& path, const RodLinkage& linkage,
                 const Eigen::Vector3d& origin) {
  write_file_atomically(path, state_text(linkage, origin));
}

namespace {

// Reads and checks the values of a state document. Messages name the JSON
// path ("segments[3].nodes[7]"), spelled only when one is reported: a state
// holds millions of values.
class StateReader {
 public:
  StateReader(const std::string& name, double size) : name_(name), size_(size) {}

  template <typename Path>
  [[noreturn]] void fail(const Path& path, const std::string& what) const {
    throw InputError(name_ + ": " + printable(path()) + ": " + what);
  }

  template <typename Path>
  const json& member(const json& object, const char* key, const Path& path) const {
    if (!object.is_object()) fail(path, "expected an object, got " + type_of(object));
    const auto it = object.find(key);
    if (it == object.end()) fail(path, std::string("missing key \"") + key + "\"");
    return *it;
  }

  template <typename Path>
  const json& array(const json& value, const Path& path) const {
    if (!value.is_array()) fail(path, "expected an array, got " + type_of(value));
    return value;
  }

  template <typename Path>
  double number(const json& value, const Path& path) const {
    if (!value.is_number()) fail(path, "expected a number, got " + type_of(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(path, "not a finite number");
    return x;
  }

  template <typename Path>
  std::vector<double> numbers(const json& value, const Path& path) const {
    std::vector<double> out;
    out.reserve(array(value, path).size());
    for (std::size_t k = 0; k < value.size(); ++k)
      out.push_back(number(value[k], [&] { return path() + "[" + std::to_string(k) + "]"; }));
    return out;
  }

  template <typename Path>
  Eigen::Vector3d vector3(const json& value, const Path& path) const {
    if (!value.is_array() || value.size() != 3)
      fail(path, "expected an array of three numbers, got " + type_of(value));
    Eigen::Vector3d v;
    for (int c = 0; c < 3; ++c)
      v[c] = number(value[c], [&] { return path() + "[" + std::to_string(c) + "]"; });
    return v;
  }

  // A position: within the coordinates a linkage may have.
  template <typename Path>
  Eigen::Vector3d point(const json& value, const Path& path) const {
    const Eigen::Vector3d p = vector3(value, path);
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate)
      fail(path, "a coordinate beyond " + text(kMaxCoordinate) +
                     " in absolute value, the largest a linkage may have");
    return p;
  }

  // A direction: of unit length.
  template <typename Path>
  Eigen::Vector3d unit(const json& value, const Path& path) const {
    const Eigen::Vector3d v = vector3(value, path);
    if (std::abs(v.norm() - 1.0) > kFrameTolerance)
      fail(path, "not a unit vector (length " + text(v.norm()) + ")");
    return v;
  }

  template <typename Path>
  void orthogonal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Path& path) const {
    if (std::abs(a.dot(b)) > kFrameTolerance)
      fail(path, "the frame's vectors are not orthogonal (dot product " + text(a.dot(b)) + ")");
  }

  // A segment's nodes: no edge shorter than the OBJ reader's zero length.
  template <typename Path>
  void distinct(const std::vector<Eigen::Vector3d>& nodes, const Path& path) const {
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i)
      if ((nodes[i + 1] - nodes[i]).norm() <= 1e-12 * size_)
        fail(path, "nodes " + std::to_string(i) + " and " + std::to_string(i + 1) +
                       " coincide: an edge of zero length");
  }

  static std::string text(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }

 private:
  // Frames are written to 17 digits; folds and updates keep them orthonormal
  // to round-off. Anything further off was not written by xshell.
  static constexpr double kFrameTolerance = 1e-6;

  static std::string type_of(const json& value) {
    switch (value.type()) {
      case json::value_t::null:
        return "null";
      case json::value_t::object:
        return "an object";
      case json::value_t::array:
        return "an array of " + std::to_string(value.size());
      case json::value_t::string:
        return "a string";
      case json::value_t::boolean:
        return "a boolean";
      default:
        return "a number";
    }
  }

  const std::string& name_;
  double size_;  // the linkage's bounding-box diagonal
};

SegmentState read_segment(const StateReader& r, const json& s, std::size_t index,
                          const Eigen::Vector3d& shift) {
  const std::string at = "segments[" + std::to_string(index) + "]";
  const auto path = [&](const char* key) { return [&at, key] { return at + "." + key; }; };
  SegmentState seg;
  const json& nodes = r.array(r.member(s, "nodes", [&] { return at; }), path("nodes"));
  seg.nodes.reserve(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k)
    seg.nodes.push_back(
        r.point(nodes[k], [&] { return at + ".nodes[" + std::to_string(k) + "]"; }) + shift);
  r.distinct(seg.nodes, path("nodes"));
  seg.thetas = r.numbers(r.member(s, "thetas", [&] { return at; }), path("thetas"));
  const json& frames =
      r.array(r.member(s, "source_frames", [&] { return at; }), path("source_frames"));
  seg.source_frames.reserve(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const auto frame = [&] { return at + ".source_frames[" + std::to_string(k) + "]"; };
    const Eigen::Vector3d tangent =
        r.unit(r.member(frames[k], "tangent", frame), [&] { return frame() + ".tangent"; });
    const Eigen::Vector3d d1 =
        r.unit(r.member(frames[k], "d1", frame), [&] { return frame() + ".d1"; });
    r.orthogonal(tangent, d1, frame);
    seg.source_frames.push_back({tangent, d1});
  }
  seg.twist_hints = r.numbers(r.member(s, "twist_hints", [&] { return at; }), path("twist_hints"));
  return seg;
}

JointState read_joint(const StateReader& r, const json& j, std::size_t index, int vertex,
                      JointKind kind, const Eigen::Vector3d& shift) {
  const std::string at = "joints[" + std::to_string(index) + "]";
  const auto where = [&at] { return at; };
  if (const auto v = j.is_object() ? j.find("vertex") : j.end();
      v != j.end() && (!v->is_number_integer() || *v != vertex))
    r.fail([&] { return at + ".vertex"; },
           "expected vertex " + std::to_string(vertex) + ", the joint's vertex in this linkage");
  JointState js;
  js.kind = kind;
  const json& params = r.member(j, "params", where);
  const auto params_path = [&at] { return at + ".params"; };
  const std::vector<double> p = r.numbers(params, params_path);
  if (p.size() != 9)
    r.fail(params_path, "a joint needs 9 parameters, got " + std::to_string(p.size()));
  for (int k = 0; k < 9; ++k) {
    if (std::abs(p[k]) > kMaxCoordinate)
      r.fail([&] { return at + ".params[" + std::to_string(k) + "]"; },
             "out of range: " + StateReader::text(p[k]));
    js.params[k] = p[k];
  }
  js.params.segment<3>(kPosition) += shift;
  const json& frame = r.member(j, "reference_frame", where);
  const auto frame_path = [&at] { return at + ".reference_frame"; };
  if (!frame.is_array() || frame.size() != 3)
    r.fail(frame_path, "expected three vectors [[...], [...], [...]]");
  for (int c = 0; c < 3; ++c)
    js.reference_frame.col(c) =
        r.unit(frame[c], [&] { return frame_path() + "[" + std::to_string(c) + "]"; });
  const Eigen::Matrix3d& f = js.reference_frame;
  if (kind == JointKind::Rotation) {
    // [b1 b2 n0]: a rotation.
    const double error = (f.transpose() * f - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (error > 1e-6 || f.determinant() < 0)
      r.fail(frame_path, "not a rotation (orthonormal and right-handed): |R^T R - I| = " +
                             StateReader::text(error) +
                             ", det R = " + StateReader::text(f.determinant()));
  } else {
    // [t0_A t0_B n0]: the normal orthogonal to both directions.
    r.orthogonal(f.col(0), f.col(2), frame_path);
    r.orthogonal(f.col(1), f.col(2), frame_path);
  }
  return js;
}

}  // namespace

void restore_state(const std::string& text, const std::string& name, RodLinkage& linkage,
                   const Eigen::Vector3d& origin) {
  const json doc = parse_json(text, name);
  // Compared as JSON values: a "format" that is not a string is not ours.
  const auto format = doc.is_object() ? doc.find("format") : doc.end();
  if (format == doc.end() || *format != "xshell-state")
    throw InputError(name + ": not an xshell state file");
  try {
    const json expected = fingerprint(linkage);
    const json& saved = doc.at("fingerprint");
    if (saved != expected) {
      const json saved_graph = without_rest_lengths(saved);
      const json expected_graph = without_rest_lengths(expected);
      if (saved_graph == expected_graph)
        throw InputError(name + ": " + rest_lengths_difference(saved, expected));
      throw InputError(name + ": the state belongs to another linkage (its fingerprint " +
                       printable(saved_graph.dump()) + " differs from this run's " +
                       expected_graph.dump() + ")");
    }
    const double size = bounding_box(linkage.graph().vertices).diagonal().norm();
    const StateReader r(name, size);
    // The same graph has the same bounding-box centre: the saved origin is
    // this run's (to round-off).
    const Eigen::Vector3d saved_origin =
        r.point(doc.at("origin"), [] { return std::string("origin"); });
    if ((saved_origin - origin).norm() > 1e-9 * std::max(size, origin.norm()))
      r.fail([] { return std::string("origin"); },
             "not this linkage's origin (the centre of its bounding box)");
    const Eigen::Vector3d shift = saved_origin - origin;  // zero for the same graph
    LinkageState state;
    const JointKind kind = joint_kind(doc);
    const json& segments = r.array(doc.at("segments"), [] { return std::string("segments"); });
    for (std::size_t s = 0; s < segments.size(); ++s)
      state.segments.push_back(read_segment(r, segments[s], s, shift));
    const json& joints = r.array(doc.at("joints"), [] { return std::string("joints"); });
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const int vertex =
          j < linkage.topology().joints.size() ? linkage.topology().joints[j].vertex : -1;
      state.joints.push_back(read_joint(r, joints[j], j, vertex, kind, shift));
    }
    linkage.restore(state);
    // What the checks above cannot see (a rod folded back on itself, a twist
    // of 1e300 radians) shows in the energy a run would start from.
    if (!std::isfinite(linkage.energy().total()))
      throw InputError(name + ": the state's elastic energy is not finite (a rod folded back " +
                       "on itself, or values beyond any physical range)");
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(name + ": malformed state file (" + printable(e.what()) + ")");
  }
}

void read_state(const std::string& path, RodLinkage& linkage, const Eigen::Vector3d& origin) {
  const std::string shown = printable(path);  // the name as messages quote it
  const std::string text =
      read_input_file(path, kStateFile, shown + ": cannot read the state file");
  restore_state(text, shown, linkage, origin);
}

}  // namespace xshell
