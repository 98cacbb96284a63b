// Per-segment loops of the linkage over OpenMP threads: the size below
// which they stay on one thread, and a loop that carries an exception out
// of the parallel region.
#pragma once

#include <exception>

namespace xshell {

// Below this many segments a per-segment loop stays on one thread: the fork
// and barriers of a parallel region cost more than they save.
constexpr int kMinParallelSegments = 32;

// f(s) for s = 0 .. count - 1, in parallel; the first exception is rethrown.
template <class F>
void for_each_segment(int count, F&& f) {
  std::exception_ptr failure;
#pragma omp parallel for schedule(static) if (count >= kMinParallelSegments)
  for (int s = 0; s < count; ++s) {
    try {
      f(s);
    } catch (...) {
#pragma omp critical(xshell_segment_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace xshell
