#include "integrators/linear_algebra/cholmod_threads.hpp"

#include <dlfcn.h>
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

// Serial guards this thread holds (nested ones included): while there is
// one its parallel regions run as plain calls (see GOMP_parallel below).
thread_local int serial_here = 0;

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
  ++serial_here;
}

CholmodThreads::~CholmodThreads() {
  if (!serial_) return;
  --serial_here;
  {
    std::lock_guard<std::mutex> lock(guard_mutex);
    if (--holders == 0) omp_set_max_active_levels(saved_levels);
  }
  omp_set_num_threads(threads_);
}

}  // namespace xshell

// libgomp's entry to a parallel region, which CHOLMOD calls once per
// supernode and loop (thousands of times per factorization). An inactive
// region still builds a team of one and ends it with a futex wake-up system
// call (about 1.2 us on this machine kind): 1.3 million of them, 1.5 s of
// system time, in a 4 s deployment of manta_ray. While this thread holds a
// serial guard the region's body is called directly: outside any team
// omp_get_num_threads() is 1 and omp_get_thread_num() 0, which is all that
// CHOLMOD's regions ask (its library imports nothing else from libgomp;
// the BLAS, told one thread, opens none). Otherwise libgomp's own entry
// runs. The definition here takes the place of libgomp's for the program
// and the libraries it loads (the dynamic linker looks in the executable
// first); in the Python module, loaded into another program, CHOLMOD may
// bind to either, and both are correct.
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  using Entry = void (*)(void (*)(void*), void*, unsigned, unsigned);
  static const Entry next = reinterpret_cast<Entry>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  if (xshell::serial_here || next == nullptr) {
    fn(data);
    return;
  }
  next(fn, data, num_threads, flags);
}
