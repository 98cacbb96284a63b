// The threads that assemble the linkage's derivatives: a team of persistent
// workers whose idle members sleep.
//
// It replaces OpenMP's parallel regions for the assembly. libgomp's idle
// workers spin for 300,000 pause instructions (about 15 ms on this machine
// kind) after every region before they sleep, and a program cannot change
// that once libgomp has read its environment (OMP_WAIT_POLICY), which it
// does before main. Between the assembly's regions the solver runs serial
// work (the factorization, the constraint's Schur complement), so a spinning
// worker held the second core that the VTK writer thread and the deployment
// plot need: manta_ray's deployment took 2.3-2.6 s with spinning workers
// against 1.9-2.0 s with OMP_WAIT_POLICY=passive (3 alternating runs each).
// Here a waiting thread spins at most 50 microseconds, then blocks.
//
// The team's size follows OpenMP's thread count (omp_get_max_threads:
// OMP_NUM_THREADS, omp_set_num_threads), so the usual controls still apply.
#pragma once

#include <exception>

namespace xshell {

class ThreadTeam {
 public:
  // The process's team (workers are started on first use, kept until exit).
  static ThreadTeam& shared();

  // f(member, members) on `members` threads, the caller being member 0;
  // returns when every member has returned. Runs f(0, 1) on the caller
  // alone when members <= 1, when called from inside a run (nesting), or
  // while another thread runs the team. The first exception a member throws
  // is rethrown here; a member must not throw while others can still wait
  // for it at a barrier.
  template <class F>
  void run(int members, F&& f) {
    run_erased(
        members, [](void* fn, int m, int n) { (*static_cast<F*>(fn))(m, n); },
        static_cast<void*>(&f));
  }

  // Inside a run: waits until every member of the run has arrived. Outside
  // a run, or in a run of one, returns at once.
  static void barrier();

  ~ThreadTeam();
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;

 private:
  ThreadTeam();
  using Job = void (*)(void*, int, int);
  void run_erased(int members, Job job, void* fn);
  struct Impl;
  Impl* impl_;
};

// The thread count OpenMP would use for a region (1 without OpenMP).
int assembly_threads();

// Member `self`'s share [first, last) of `count` items split into `members`
// consecutive ranges (a static schedule).
struct MemberRange {
  long first, last;
};
inline MemberRange member_range(long count, int self, int members) {
  return {count * self / members, count * (self + 1) / members};
}

}  // namespace xshell
