// What the benchmark measures with, apart from the model: medians, clocks,
// the cores it may run on, its peak memory, and the BLAS that CHOLMOD calls.
#pragma once

#include <sched.h>

#include <chrono>
#include <string>
#include <vector>

namespace xshell::bench {

// Median of v (NAN when empty).
double median(std::vector<double> v);

// Process CPU time (all threads), seconds.
double cpu_seconds();

// Median wall time (ms) of reps runs of f; with cpu_ms, also the median CPU time.
template <class F>
double median_ms(int reps, F&& f, double* cpu_ms = nullptr) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> t, c;
  for (int i = 0; i < reps; ++i) {
    const double cpu = cpu_seconds();
    const Clock::time_point start = Clock::now();
    f();
    t.push_back(1e3 * std::chrono::duration<double>(Clock::now() - start).count());
    c.push_back(1e3 * (cpu_seconds() - cpu));
  }
  if (cpu_ms) *cpu_ms = median(c);
  return median(t);
}

// The first `count` cores the process may run on (fewer when it may use
// fewer).
std::vector<int> allowed_cores(int count);

// Keeps the calling thread on one core while it lives, then restores the
// cores it had.
class PinnedThread {
 public:
  explicit PinnedThread(int core);
  ~PinnedThread();
  PinnedThread(const PinnedThread&) = delete;
  PinnedThread& operator=(const PinnedThread&) = delete;

 private:
  cpu_set_t saved_;
  bool pinned_ = false;
};

// The process's peak resident memory so far, MB.
double peak_rss_mb();

// The file of the BLAS that CHOLMOD calls (where dsyrk_ resolves).
std::string loaded_blas();

}  // namespace xshell::bench
