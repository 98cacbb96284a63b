#include "state_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "atomic_file.hpp"
#include "input_error.hpp"

namespace xshell {

namespace {
using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d to_vec(const json& j) {
  if (!j.is_array() || j.size() != 3) throw std::invalid_argument("expected a 3-vector");
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

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
  return out;
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

void write_state(const std::string& path, const RodLinkage& linkage,
                 const Eigen::Vector3d& origin) {
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
  write_file_atomically(path, doc.dump() + "\n");
}

void read_state(const std::string& path, RodLinkage& linkage, const Eigen::Vector3d& origin) {
  std::error_code ignored;  // a folder opens as a stream that fails only when read
  if (std::filesystem::is_directory(path, ignored))
    throw InputError(path + ": cannot read the state file: it is a folder, not a file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the state file: " + std::strerror(errno));
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path + ": not a valid state file (" + e.what() + ")");
  }
  try {
    if (doc.value("format", "") != "xshell-state")
      throw InputError(path + ": not an xshell state file");
    const json expected = fingerprint(linkage);
    if (doc.at("fingerprint") != expected)
      throw InputError(path + ": the state belongs to another linkage (its fingerprint " +
                       doc.at("fingerprint").dump() + " differs from this run's " +
                       expected.dump() + ")");
    const Eigen::Vector3d saved_origin = to_vec(doc.at("origin"));
    const Eigen::Vector3d shift = saved_origin - origin;  // zero for the same graph
    LinkageState state;
    const JointKind kind = joint_kind(doc);
    for (const json& s : doc.at("segments")) {
      SegmentState seg;
      for (const json& x : s.at("nodes")) seg.nodes.push_back(to_vec(x) + shift);
      seg.thetas = s.at("thetas").get<std::vector<double>>();
      for (const json& f : s.at("source_frames"))
        seg.source_frames.push_back({to_vec(f.at("tangent")), to_vec(f.at("d1"))});
      seg.twist_hints = s.at("twist_hints").get<std::vector<double>>();
      state.segments.push_back(std::move(seg));
    }
    for (const json& j : doc.at("joints")) {
      JointState js;
      js.kind = kind;
      const std::vector<double> p = j.at("params").get<std::vector<double>>();
      if (p.size() != 9) throw std::invalid_argument("a joint needs 9 parameters");
      for (int k = 0; k < 9; ++k) js.params[k] = p[k];
      js.params.segment<3>(kPosition) += shift;
      for (int c = 0; c < 3; ++c) js.reference_frame.col(c) = to_vec(j.at("reference_frame").at(c));
      state.joints.push_back(js);
    }
    linkage.restore(state);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path + ": malformed state file (" + e.what() + ")");
  }
}

}  // namespace xshell
