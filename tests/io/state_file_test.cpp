// state.json (io/state_file.hpp): a state is restored exactly, and one that
// xshell would not have written is refused like a bad configuration, with
// the JSON path of what is wrong.
#include "io/state_file.hpp"

#include <doctest/doctest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "scratch_directory.hpp"

namespace xshell::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One X joint (vertex 2) and four free ends, not centred at the origin.
RodLinkage cross_linkage(JointKind kind = JointKind::Rotation) {
  std::istringstream obj("v 9 9 1\nv 11 11 1\nv 10 10 1\nv 11 9 1\nv 9 11 1\nl 1 3 2\nl 4 3 5\n");
  LinkageOptions options;
  options.subdivisions = 4;
  options.joint_kind = kind;
  options.material.young_modulus = 1e4;
  LineGraph graph = parse_obj(obj, "x.obj");
  for (auto& v : graph.vertices) v -= Eigen::Vector3d(10, 10, 1);  // recentred
  return RodLinkage(graph, options);
}
const Eigen::Vector3d kOrigin(10, 10, 1);

// The state of a linkage moved off its input (so that restoring it shows).
json written_state(JointKind kind = JointKind::Rotation) {
  RodLinkage linkage = cross_linkage(kind);
  Eigen::VectorXd q = linkage.dofs();
  for (int i = 0; i < q.size(); ++i) q[i] += 1e-3 * std::sin(1.0 + i);
  linkage.set_dofs(q);
  const ScratchDirectory dir("state");
  write_state((dir / "state.json").string(), linkage, kOrigin);
  std::ifstream in(dir / "state.json");
  return json::parse(in);
}

// The message of the InputError that restoring `doc` raises ("" and a
// failed check when it is accepted).
std::string refusal(const json& doc, JointKind kind = JointKind::Rotation) {
  RodLinkage linkage = cross_linkage(kind);
  try {
    restore_state(doc.dump(), "s.json", linkage, kOrigin);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL_CHECK("accepted");
  return "";
}

void check_message(const std::string& message, const std::vector<std::string>& words) {
  INFO("message: " << message);
  CHECK(message.rfind("s.json", 0) == 0);
  for (const auto& w : words) CHECK_MESSAGE(message.find(w) != std::string::npos, "missing: " << w);
}

}  // namespace

TEST_CASE("state file: a written state restores the linkage exactly") {
  int checked = 0;
  for (const JointKind kind : {JointKind::Rotation, JointKind::EdgeVectors}) {
    const json doc = written_state(kind);
    RodLinkage restored = cross_linkage(kind);
    restore_state(doc.dump(), "s.json", restored, kOrigin);
    const ScratchDirectory dir("state-again");
    write_state((dir / "state.json").string(), restored, kOrigin);
    std::ifstream in(dir / "state.json");
    CHECK(json::parse(in) == doc);
    ++checked;
  }
  CHECK(checked == 2);
}

TEST_CASE("state file: a reference frame that is no rotation is refused naming the joint") {
  json doc = written_state();
  doc["joints"][0]["reference_frame"][1] = {0.0, 0.8, 0.6};  // unit, not orthogonal to b1
  const json b1 = doc["joints"][0]["reference_frame"][0];
  INFO("b1 = " << b1.dump());
  check_message(refusal(doc), {"joints[0].reference_frame", "not a rotation"});
  doc = written_state();
  for (auto& c : doc["joints"][0]["reference_frame"][2]) c = -c.get<double>();  // reflection
  check_message(refusal(doc), {"joints[0].reference_frame", "right-handed"});
  doc = written_state();
  doc["joints"][0]["reference_frame"][0] = {2.0, 0.0, 0.0};
  check_message(refusal(doc), {"joints[0].reference_frame[0]", "not a unit vector"});
  doc = written_state();
  doc["segments"][1]["source_frames"][2]["d1"] = doc["segments"][1]["source_frames"][2]["tangent"];
  check_message(refusal(doc), {"segments[1].source_frames[2]", "not orthogonal"});
}

TEST_CASE("state file: an origin far off or coordinates beyond the linkage range are refused") {
  json doc = written_state();
  doc["origin"] = {1e300, 0, 0};
  check_message(refusal(doc), {"s.json: origin: a coordinate beyond 1e+12"});
  doc["origin"] = {10.5, 10, 1};  // in range, but not this linkage's centre
  check_message(refusal(doc), {"s.json: origin: not this linkage's origin"});
  doc = written_state();
  doc["segments"][0]["nodes"][1][2] = 1e200;
  check_message(refusal(doc), {"s.json: segments[0].nodes[1]: a coordinate beyond"});
  doc = written_state();
  doc["joints"][0]["params"][0] = -1e13;
  check_message(refusal(doc), {"s.json: joints[0].params[0]: out of range"});
}

TEST_CASE("state file: nodes on top of each other (every node at 0) are refused") {
  json doc = written_state();
  for (auto& segment : doc["segments"])
    for (auto& node : segment["nodes"]) node = {0.0, 0.0, 0.0};
  check_message(refusal(doc), {"s.json: segments[0].nodes: nodes 0 and 1 coincide"});
}

TEST_CASE("state file: a state whose energy is not finite is refused") {
  json doc = written_state();
  doc["segments"][0]["thetas"][1] = 1e300;  // finite, but its twist energy is not
  check_message(refusal(doc), {"s.json: the state's elastic energy is not finite"});
}

TEST_CASE("state file: values of the wrong type are refused with their path") {
  json doc = written_state();
  doc["segments"][0]["thetas"][1] = nullptr;  // how nlohmann writes NaN
  check_message(refusal(doc), {"s.json: segments[0].thetas[1]: expected a number, got null"});
  doc = written_state();
  doc["segments"][2].erase("twist_hints");
  check_message(refusal(doc), {"s.json: segments[2]: missing key \"twist_hints\""});
  doc = written_state();
  doc["joints"][0]["params"].erase(8);
  check_message(refusal(doc), {"s.json: joints[0].params: a joint needs 9 parameters, got 8"});
  doc = written_state();
  doc["joints"][0]["vertex"] = 1;
  check_message(refusal(doc), {"s.json: joints[0].vertex: expected vertex 2"});
  check_message(refusal(json::array()), {"s.json: not an xshell state file"});
  doc = written_state();
  doc["format"] = {0, 0, 0};  // a "format" of another type is not ours either
  check_message(refusal(doc), {"s.json: not an xshell state file"});
  doc = written_state();
  doc["joint_kind"] = {1};
  check_message(refusal(doc), {"s.json: malformed state file"});
  RodLinkage linkage = cross_linkage();
  CHECK_THROWS_WITH_AS(restore_state("{\"format\": ", "s.json", linkage, kOrigin),
                       doctest::Contains("s.json:1:12: invalid JSON"), InputError);
  CHECK_THROWS_WITH_AS(
      restore_state(std::string(100, '[') + std::string(100, ']'), "s.json", linkage, kOrigin),
      doctest::Contains("nested deeper than 64"), InputError);
}

TEST_CASE("state file: a FIFO or a folder is refused without blocking") {
  const ScratchDirectory scratch("state-kinds");
  const fs::path& dir = scratch.path();
  REQUIRE(::mkfifo((dir / "fifo.json").c_str(), 0600) == 0);
  RodLinkage linkage = cross_linkage();
  CHECK_THROWS_WITH_AS(read_state((dir / "fifo.json").string(), linkage, kOrigin),
                       doctest::Contains("cannot read the state file: it is a FIFO"), InputError);
  CHECK_THROWS_WITH_AS(read_state(dir.string(), linkage, kOrigin),
                       doctest::Contains("cannot read the state file: it is a folder"), InputError);
}

}  // namespace xshell::test
