// A loop over [0, count) inside a parallel run (thread_team.hpp) that gives every
// thread the same consecutive range at every call, as a static schedule
// does, and lets a thread that has finished its own range take what is left
// of the others' (work stealing).
//
// The two schedules it replaces each fail on this kind of machine:
// - dynamic schedules hand an item to either thread at random, so the data
//   it writes (rods' derivatives, value slots, joint geometry) moves between
//   the cores' caches at every call: a 40-segment Hessian was 1.65x faster
//   on 2 threads than on 1;
// - static schedules keep the data in place but wait for the slowest
//   thread, and a virtual machine's two cores are not always equally fast:
//   two single-threaded copies of the same Hessian, run side by side, took
//   3.4 and 4.7-5.3 ms.
// Here an item leaves its thread only when the thread falls behind.
#pragma once

#include <algorithm>
#include <atomic>
#include <memory>

namespace xshell {

class AffineLoop {
 public:
  AffineLoop() = default;
  // A copy has no ranges yet: they belong to one run, and reset() makes them.
  AffineLoop(const AffineLoop&) {}
  AffineLoop& operator=(const AffineLoop&) {
    cursors_.reset();
    threads_ = 0;
    return *this;
  }
  AffineLoop(AffineLoop&&) noexcept = default;
  AffineLoop& operator=(AffineLoop&&) noexcept = default;

  // Sets the ranges for `count` items over a team of `threads`: call from
  // one member, with a barrier before any member runs it.
  void reset(int count, int threads) {
    if (threads != threads_) {
      cursors_ = std::make_unique<Cursor[]>(threads);
      threads_ = threads;
    }
    for (int t = 0; t < threads; ++t) {
      cursors_[t].next.store(static_cast<int>(static_cast<long>(count) * t / threads),
                             std::memory_order_relaxed);
      cursors_[t].end = static_cast<int>(static_cast<long>(count) * (t + 1) / threads);
    }
  }

  // f(i) for every item, each exactly once over the team, in chunks of
  // `chunk` items: every member `self` runs this, its own range first, then
  // what is left of the next members' ranges. No barrier at the end.
  template <class F>
  void run(int self, int chunk, F&& f) {
    for (int k = 0; k < threads_; ++k) {
      Cursor& c = cursors_[(self + k) % threads_];
      for (;;) {
        const int first = c.next.fetch_add(chunk, std::memory_order_relaxed);
        if (first >= c.end) break;
        const int last = std::min(first + chunk, c.end);
        for (int i = first; i < last; ++i) f(i);
      }
    }
  }

 private:
  struct alignas(64) Cursor {
    std::atomic<int> next{0};
    int end = 0;
  };
  std::unique_ptr<Cursor[]> cursors_;
  int threads_ = 0;
};

}  // namespace xshell
