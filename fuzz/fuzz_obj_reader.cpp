// Fuzzes the OBJ line-mesh reader: any input either parses into a valid
// graph or is rejected with an InputError; anything else (a crash, another
// exception, a sanitizer report) is a finding.
#include <cstdint>
#include <sstream>
#include <string>

#include "io/input_error.hpp"
#include "io/obj_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const xshell::LineGraph graph = xshell::parse_obj(in, "fuzz.obj");
    // A graph that passed must be usable: every edge names two vertices.
    for (const auto& e : graph.edges)
      if (e[0] < 0 || e[1] < 0 || e[0] >= static_cast<int>(graph.vertices.size()) ||
          e[1] >= static_cast<int>(graph.vertices.size()))
        __builtin_trap();
  } catch (const xshell::InputError&) {
  }
  return 0;
}
