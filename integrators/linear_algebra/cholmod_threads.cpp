#include "integrators/linear_algebra/cholmod_threads.hpp"

#include <omp.h>

#include <mutex>

namespace xshell {

namespace {

// The limit on active parallel levels is one per program (libgomp), so
// guards held at the same time by several threads share it: the first sets
// it to 0 (every region inactive, one thread), the last restores it.
std::mutex guard_mutex;
int holders = 0;
int saved_levels = 0;

}  // namespace

CholmodThreads::CholmodThreads() {
  threads_ = omp_get_max_threads();
  if (threads_ >= kCholmodTeamSize) return;
  // The BLAS sizes its teams by the thread count and synchronizes their
  // members by spinning: in a region made inactive, a team it believes has
  // two members would wait forever for the second. So it is told one.
  omp_set_num_threads(1);
  std::lock_guard<std::mutex> lock(guard_mutex);
  if (holders++ == 0) {
    saved_levels = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
  }
  serial_ = true;
}

CholmodThreads::~CholmodThreads() {
  if (!serial_) return;
  {
    std::lock_guard<std::mutex> lock(guard_mutex);
    if (--holders == 0) omp_set_max_active_levels(saved_levels);
  }
  omp_set_num_threads(threads_);
}

}  // namespace xshell
