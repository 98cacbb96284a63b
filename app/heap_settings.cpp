#include "heap_settings.hpp"

#include <mutex>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#endif

namespace xshell {

namespace {

#if defined(__GLIBC__)
// Grows the heap by 240 MiB of untouched address space (under
// M_TRIM_THRESHOLD: it stays) and asks for transparent huge pages on the
// whole heap (best effort: errors are ignored).
void advise_huge_heap() {
  constexpr std::uintptr_t kHugePage = 2u << 20;
  mallopt(M_TOP_PAD, 224 << 20);                 // the next growth of the heap adds 224 MiB
  void* volatile block = std::malloc(16 << 20);  // below M_MMAP_THRESHOLD: grows the heap
  std::free(block);                              // below M_TRIM_THRESHOLD: stays
  mallopt(M_TOP_PAD, 128 << 10);                 // glibc's default
  const std::uintptr_t top = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t heap = mallinfo2().arena;  // the main heap's size, from brk
  if (heap == 0 || heap > top) return;
  const std::uintptr_t begin = (top - heap + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t end = top & ~(kHugePage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}
#endif

}  // namespace

void keep_freed_heap() {
  static std::once_flag once;
  std::call_once(once, [] {
#if defined(__GLIBC__)
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    advise_huge_heap();
#endif
  });
}

}  // namespace xshell
