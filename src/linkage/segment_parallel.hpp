// Per-segment loops of the linkage over the assembly's threads
// (thread_team.hpp): the size below which they stay on one thread, and a
// loop that carries an exception out of the parallel run.
#pragma once

#include <exception>
#include <mutex>

#include "linkage/thread_team.hpp"

namespace xshell {

// Below this many segments a per-segment loop stays on one thread: waking
// the team and its barriers cost more than they save.
constexpr int kMinParallelSegments = 32;

// The team size of a per-segment run over `count` segments.
inline int segment_threads(int count) {
  return count >= kMinParallelSegments ? assembly_threads() : 1;
}

// f(s) for s = 0 .. count - 1, in parallel; the first exception is rethrown.
template <class F>
void for_each_segment(int count, F&& f) {
  std::exception_ptr failure;
  std::mutex failure_mutex;
  ThreadTeam::shared().run(segment_threads(count), [&](int self, int size) {
    const MemberRange range = member_range(count, self, size);
    for (long s = range.first; s < range.last; ++s) {
      try {
        f(static_cast<int>(s));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  });
  if (failure) std::rethrow_exception(failure);
}

}  // namespace xshell
