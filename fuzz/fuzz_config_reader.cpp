// Fuzzes the configuration reader: any text either parses into a
// configuration or is rejected with an InputError.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "io/config.hpp"
#include "io/input_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const xshell::Config config = xshell::parse_config(
        std::string(reinterpret_cast<const char*>(data), size), "fuzz.json", "");
    (void)xshell::to_json(config);
  } catch (const xshell::InputError&) {
  }
  return 0;
}
