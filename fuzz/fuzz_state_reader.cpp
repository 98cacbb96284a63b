// Fuzzes the state reader (`--init STATE.json`): any text either restores a
// state of the small linkage below (fuzz/corpus/obj/cross.obj at 3
// subdivisions, the linkage of the corpus in fuzz/corpus/state/) or is
// rejected with an InputError. Anything else is a finding: a crash, another
// exception, a sanitizer report, or a restored state whose energy is not
// finite (a state that passes must be one a run can start from).
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/state_file.hpp"

namespace {

const xshell::RodLinkage& pristine() {
  static const xshell::RodLinkage linkage = [] {
    std::istringstream obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nl 2 1 4\nl 3 1 5\n");
    xshell::LinkageOptions options;
    options.subdivisions = 3;
    options.material.young_modulus = 2e10;
    options.material.section = {xshell::SectionShape::Rectangle, 0.01, 0.007};
    return xshell::RodLinkage(xshell::parse_obj(obj, "cross.obj"), options);
  }();
  return linkage;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  xshell::RodLinkage linkage = pristine();
  try {
    xshell::restore_state(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json",
                          linkage, Eigen::Vector3d::Zero());
  } catch (const xshell::InputError&) {
    return 0;
  }
  if (!std::isfinite(linkage.energy().total())) __builtin_trap();
  return 0;
}
