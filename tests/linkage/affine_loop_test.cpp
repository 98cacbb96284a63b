// AffineLoop (affine_loop.hpp): every item exactly once, each thread's own
// range first, and a thread that is held back has its range taken over.
#include "linkage/affine_loop.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <vector>

#include "linkage/thread_team.hpp"

namespace xshell::test {

namespace {

// Runs the loop over `count` items on `threads` threads (chunk `chunk`),
// recording which thread took each item and how often it was taken.
struct Record {
  std::vector<int> owner, times;
};
Record run_loop(AffineLoop& loop, int count, int threads, int chunk) {
  Record r{std::vector<int>(count, -1), std::vector<int>(count, 0)};
  std::vector<std::atomic<int>> times(count);
  ThreadTeam::shared().run(threads, [&](int self, int members) {
    if (self == 0) loop.reset(count, members);
    ThreadTeam::barrier();
    loop.run(self, chunk, [&](int i) {
      ++times[i];
      r.owner[i] = self;
    });
  });
  for (int i = 0; i < count; ++i) r.times[i] = times[i].load();
  return r;
}

}  // namespace

TEST_CASE(
    "AffineLoop runs every item exactly once, for any team and chunk, and again after a reset") {
  AffineLoop loop;
  int checked = 0;
  for (int threads : {1, 2, 3})
    for (int count : {0, 1, 2, 7, 40, 1001})
      for (int chunk : {1, 2, 5})
        for (int repeat = 0; repeat < 2; ++repeat) {
          const Record r = run_loop(loop, count, threads, chunk);
          for (int i = 0; i < count; ++i) {
            CHECK(r.times[i] == 1);
            CHECK(r.owner[i] >= 0);
            CHECK(r.owner[i] < threads);
            ++checked;
          }
        }
  CHECK(checked == 2 * 3 * 3 * (0 + 1 + 2 + 7 + 40 + 1001));
}

namespace {
// Runs the loop over `count` items on 2 threads, thread `held` starting only
// when the other has finished: the order in which each thread took items,
// or nothing when the team has fewer than 2 threads.
std::vector<std::vector<int>> run_held_back(AffineLoop& loop, int count, int held) {
  std::vector<std::vector<int>> order(2);
  std::atomic<bool> other_done{false};
  ThreadTeam::shared().run(2, [&](int self, int members) {
    if (self == 0) loop.reset(count, members);
    ThreadTeam::barrier();
    if (members == 2) {
      if (self == held)
        while (!other_done.load()) {
        }
      loop.run(self, 1, [&](int i) { order[self].push_back(i); });
      if (self != held) other_done.store(true);
    }
  });
  return order;
}
}  // namespace

TEST_CASE(
    "AffineLoop: a thread takes its own consecutive range first, and the others' when they are "
    "held back") {
  AffineLoop loop;
  const int count = 50;
  std::vector<int> expected(count);
  // Thread 1 held back: thread 0 takes its range [0, 25), then thread 1's.
  for (int k = 0; k < count; ++k) expected[k] = k;
  std::vector<std::vector<int>> order = run_held_back(loop, count, 1);
  REQUIRE(order[0].size() + order[1].size() > 0);  // a team of 2
  CHECK(order[0] == expected);
  CHECK(order[1].empty());
  // Thread 0 held back: thread 1 takes [25, 50) first, then [0, 25).
  for (int k = 0; k < count; ++k) expected[k] = k < 25 ? 25 + k : k - 25;
  order = run_held_back(loop, count, 0);
  CHECK(order[1] == expected);
  CHECK(order[0].empty());
}

}  // namespace xshell::test
