// The heap's huge-page advice (app/heap_settings.hpp): after
// keep_freed_heap(), a block from the heap lies in a mapping flagged for
// transparent huge pages ("hg" in /proc/self/smaps).
#include "app/heap_settings.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "skip.hpp"

namespace xshell::test {
namespace {

// The VmFlags line of the mapping of /proc/self/smaps that holds `address`.
std::string mapping_flags(std::uintptr_t address) {
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= address && address < end;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

}  // namespace

TEST_CASE("heap: keep_freed_heap advises transparent huge pages for the heap's blocks") {
#if defined(__SANITIZE_ADDRESS__)
  XSHELL_SKIP("the address sanitizer's allocator is not the C library's heap");
#endif
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled"))
    XSHELL_SKIP("this system has no transparent huge pages");
  keep_freed_heap();
  // 8 MiB from the heap (below M_MMAP_THRESHOLD); its middle lies past the
  // heap's first, partial 2 MiB, which the advice leaves out.
  constexpr std::size_t kSize = 8 << 20;
  void* volatile block = std::malloc(kSize);
  REQUIRE(block != nullptr);
  const std::string flags = mapping_flags(reinterpret_cast<std::uintptr_t>(block) + kSize / 2);
  std::free(block);
  CAPTURE(flags);
  REQUIRE(!flags.empty());
  CHECK(flags.find(" hg") != std::string::npos);
  keep_freed_heap();  // once per process: a second call changes nothing
}

}  // namespace xshell::test
