// ThreadTeam (thread_team.hpp): every member once per run, barriers that
// order the members' phases, serial runs when nested or when the team is
// busy, exceptions carried out, and workers that sleep when idle.
#include "linkage/thread_team.hpp"

#include <doctest/doctest.h>
#include <time.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace xshell::test {

namespace {

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

TEST_CASE("A team run calls every member once, the caller as member 0") {
  ThreadTeam& team = ThreadTeam::shared();
  int runs = 0;
  for (int members : {1, 2, 3, 2, 1}) {
    std::vector<std::atomic<int>> calls(static_cast<size_t>(members));
    std::atomic<int> wrong_size{0}, caller_not_zero{0};
    const std::thread::id caller = std::this_thread::get_id();
    team.run(members, [&](int self, int size) {
      if (size != members) ++wrong_size;
      if ((std::this_thread::get_id() == caller) != (self == 0)) ++caller_not_zero;
      ++calls[static_cast<size_t>(self)];
    });
    for (auto& c : calls) CHECK(c.load() == 1);
    CHECK(wrong_size.load() == 0);
    CHECK(caller_not_zero.load() == 0);
    ++runs;
  }
  CHECK(runs == 5);
}

TEST_CASE("Team barriers order the members' phases, run after run") {
  ThreadTeam& team = ThreadTeam::shared();
  const int members = 3, phases = 4, repeats = 500;
  int bad = 0, checked = 0;
  for (int r = 0; r < repeats; ++r) {
    std::vector<std::atomic<int>> done(members * phases);
    std::atomic<int> early{0};
    team.run(members, [&](int self, int size) {
      for (int p = 0; p < phases; ++p) {
        done[static_cast<size_t>(p * size + self)] = 1;
        ThreadTeam::barrier();
        for (int m = 0; m < size; ++m)
          if (done[static_cast<size_t>(p * size + m)].load() != 1) ++early;
      }
    });
    bad += early.load();
    ++checked;
  }
  CHECK(bad == 0);
  CHECK(checked == repeats);
}

TEST_CASE("A run inside a run, or beside another thread's, is serial on its caller") {
  ThreadTeam& team = ThreadTeam::shared();
  std::atomic<int> nested_calls{0}, nested_wrong{0};
  team.run(2, [&](int self, int) {
    const std::thread::id me = std::this_thread::get_id();
    team.run(2, [&](int inner, int size) {
      ++nested_calls;
      if (inner != 0 || size != 1 || std::this_thread::get_id() != me) ++nested_wrong;
      ThreadTeam::barrier();  // a run of one: returns at once
    });
    (void)self;
  });
  CHECK(nested_calls.load() == 2);
  CHECK(nested_wrong.load() == 0);

  // Another thread asks while the team is held: it runs alone.
  std::atomic<bool> holding{false}, other_done{false};
  int other_size = 0, other_calls = 0;
  team.run(2, [&](int self, int) {
    if (self != 0) return;
    holding = true;
    std::thread other([&] {
      team.run(2, [&](int, int size) {
        other_size = size;
        ++other_calls;
      });
      other_done = true;
    });
    other.join();
  });
  CHECK(holding.load());
  CHECK(other_done.load());
  CHECK(other_calls == 1);
  CHECK(other_size == 1);
}

TEST_CASE("An exception thrown by a team member comes out of the run, and the team goes on") {
  ThreadTeam& team = ThreadTeam::shared();
  for (int thrower : {0, 1}) {
    CAPTURE(thrower);
    CHECK_THROWS_AS(team.run(2,
                             [&](int self, int) {
                               if (self == thrower) throw std::runtime_error("member failed");
                             }),
                    std::runtime_error);
  }
  std::atomic<int> calls{0};
  team.run(2, [&](int, int) { ++calls; });
  CHECK(calls.load() == 2);
}

TEST_CASE("Idle team workers sleep instead of spinning") {
  ThreadTeam& team = ThreadTeam::shared();
  std::atomic<int> calls{0};
  team.run(3, [&](int, int) { ++calls; });
  REQUIRE(calls.load() == 3);
  // Any spinning left by earlier OpenMP regions of this program (libgomp's
  // workers spin about 15 ms) ends first; then, over 200 ms in which this
  // thread sleeps, the process uses almost no processor time. Two spinning
  // workers would use about 400 ms.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const double before = process_cpu_seconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const double used = process_cpu_seconds() - before;
  CHECK(used < 0.02);
}

}  // namespace xshell::test
