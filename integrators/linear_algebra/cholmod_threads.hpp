// How many OpenMP threads a CHOLMOD call may use.
//
// Debian's CHOLMOD (SuiteSparse 5) opens its own parallel regions in the
// supernodal factorization with a team size fixed at compile time
// (CHOLMOD_OMP_NUM_THREADS, 4), whatever OMP_NUM_THREADS says. On a machine
// that allows fewer threads, those teams oversubscribe the cores: the
// workers of every region wait for descheduled partners, and the idle ones
// keep waking. Measured on 2 cores (OpenBLAS, numeric factorization, medians
// of 5): the largest design at subdivision 8 (68k unknowns) 414 ms with the
// teams of 4 against 105-110 ms on one thread; hourglass (39k) 175 ms
// against 48 ms; a 4x4 grid (1k unknowns) 1.5 ms against 1.0 ms.
//
// CholmodThreads, held during a CHOLMOD call, makes every parallel region
// the call opens (CHOLMOD's and the BLAS's) run on the calling thread when
// the program allows fewer threads than CHOLMOD's teams (the limit on
// active levels 0, and the thread count 1 for the BLAS, which sizes its
// teams by it); with enough threads it changes nothing. On 2 cores the
// BLAS gained nothing from a second thread on these factorizations
// (largest design 110 ms on one thread, 104 ms on two). While a serial
// guard is held, the regions opened on its thread are plain calls that
// make no team at all (cholmod_threads.cpp, GOMP_parallel): an inactive
// region still costs a system call, and CHOLMOD opens thousands per
// factorization (manta_ray's 7-11 ms became 2.0 ms, the largest design's
// 85-105 ms 29 ms).
#pragma once

namespace xshell {

// CHOLMOD's compiled-in team size (SuiteSparse 5's default).
constexpr int kCholmodTeamSize = 4;

class CholmodThreads {
 public:
  CholmodThreads();
  ~CholmodThreads();
  CholmodThreads(const CholmodThreads&) = delete;
  CholmodThreads& operator=(const CholmodThreads&) = delete;

  // Whether the regions opened while this guard lives run on one thread.
  bool serial() const { return serial_; }

 private:
  bool serial_ = false;
  int threads_ = 1;  // the thread count before
};

}  // namespace xshell
