// The rest lengths given to a linkage ("rest_lengths" of the configuration)
// are part of its state's fingerprint (io/state_file.hpp): a state restores
// only into a linkage with the same ones, and a state without them (as every
// state written before they existed) only into one with the drawing's.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/state_file.hpp"

namespace xshell::test {
namespace {

using nlohmann::json;

// Two rods crossing at vertex 1 (four segments), centred at the origin;
// `lengths`: the segments' rest lengths (empty: the drawing's, 1 each).
RodLinkage crossing(const std::vector<double>& lengths) {
  std::istringstream obj("v -1 0 0\nv 0 0 0\nv 1 0 0\nv 0 -1 0\nv 0 1 0\nl 1 2 3\nl 4 2 5\n");
  LinkageOptions options;
  options.subdivisions = 3;
  options.rest_shape = RestShape::Straight;
  options.material.young_modulus = 1e4;
  options.segment_rest_lengths = lengths;
  return RodLinkage(parse_obj(obj, "x.obj"), options);
}

json saved(const std::vector<double>& lengths) {
  return json::parse(state_text(crossing(lengths), Eigen::Vector3d::Zero()));
}

// The message of restoring `doc` into crossing(lengths); "" when it restores.
std::string restoring(const json& doc, const std::vector<double>& lengths) {
  RodLinkage linkage = crossing(lengths);
  try {
    restore_state(doc.dump(), "s.json", linkage, Eigen::Vector3d::Zero());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::vector<double> kLonger = {1.02, 1.02, 1.0, 1.0};

}  // namespace

TEST_CASE("state file: the rest lengths given are in the fingerprint, absent when none are") {
  CHECK_FALSE(saved({})["fingerprint"].contains("rest_lengths"));
  CHECK(saved(kLonger)["fingerprint"]["rest_lengths"] == json(kLonger));
  CHECK(restoring(saved({}), {}).empty());
  CHECK(restoring(saved(kLonger), kLonger).empty());
}

TEST_CASE("state file: a state of other rest lengths is refused, saying which") {
  std::string m = restoring(saved(kLonger), {});
  CHECK(m.find("s.json: the state was saved with \"rest_lengths\", this run has the drawing's") ==
        0);
  m = restoring(saved({}), kLonger);
  CHECK(m.find("s.json: the state was saved with the drawing's rest lengths, this run gives "
               "\"rest_lengths\"") == 0);
  m = restoring(saved(kLonger), {1.02, 1.03, 1.0, 1.0});
  CHECK(m.find("(segment 1: 1.02 in the state, 1.03 in this run)") != std::string::npos);
  CHECK(m.find("start without --init") != std::string::npos);
  json bad = saved(kLonger);
  bad["fingerprint"]["rest_lengths"] = {1.02, "x", 1.0, 1.0};
  CHECK(restoring(bad, kLonger).find("malformed \"rest_lengths\"") != std::string::npos);
  // Another graph is still another linkage, whatever the rest lengths.
  bad = saved(kLonger);
  bad["fingerprint"]["subdivisions"] = 4;
  m = restoring(bad, {});
  CHECK(m.find("s.json: the state belongs to another linkage") == 0);
  CHECK(m.find("rest_lengths") == std::string::npos);
}

}  // namespace xshell::test
