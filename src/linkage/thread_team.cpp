#include "linkage/thread_team.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace xshell {

namespace {

// How long a waiting thread spins before it blocks: long enough that the
// barriers of one assembly stay in user space when the members arrive
// nearly together (a sleep and a wake-up cost tens of microseconds in a
// virtual machine), short enough that an idle worker leaves the core at
// once (libgomp's workers spin about 15 ms here).
constexpr auto kSpin = std::chrono::microseconds(50);

// Returns once ready() holds: spins up to kSpin, then blocks on `cv`
// (whoever makes ready() true notifies `cv` with `mutex` held).
template <class Ready>
void wait_until(std::mutex& mutex, std::condition_variable& cv, Ready&& ready) {
  const auto deadline = std::chrono::steady_clock::now() + kSpin;
  for (unsigned i = 1;; ++i) {
    if (ready()) return;
    if (i % 64 == 0 && std::chrono::steady_clock::now() >= deadline) break;
  }
  std::unique_lock<std::mutex> lock(mutex);
  cv.wait(lock, ready);
}

// A barrier for the members of one run.
class Barrier {
 public:
  void reset(int members) {
    members_ = members;
    arrived_.store(0, std::memory_order_relaxed);
  }

  void arrive() {
    const long generation = generation_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == members_) {
      arrived_.store(0, std::memory_order_relaxed);
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        generation_.store(generation + 1, std::memory_order_release);
      }
      cv_.notify_all();
      return;
    }
    wait_until(mutex_, cv_,
               [&] { return generation_.load(std::memory_order_acquire) != generation; });
  }

 private:
  int members_ = 1;
  std::atomic<int> arrived_{0};
  std::atomic<long> generation_{0};
  std::mutex mutex_;
  std::condition_variable cv_;
};

// The barrier of the run this thread is a member of (null outside a run or
// in a run of one), and whether it is in a run at all.
thread_local Barrier* run_barrier = nullptr;
thread_local bool in_run = false;

// Marks this thread as a member of a run for the scope.
class Membership {
 public:
  explicit Membership(Barrier* barrier) : barrier_(run_barrier), in_(in_run) {
    run_barrier = barrier;
    in_run = true;
  }
  ~Membership() {
    run_barrier = barrier_;
    in_run = in_;
  }
  Membership(const Membership&) = delete;
  Membership& operator=(const Membership&) = delete;

 private:
  Barrier* barrier_;
  bool in_;
};

}  // namespace

struct ThreadTeam::Impl {
  std::mutex run_mutex;  // one run at a time
  std::vector<std::thread> workers;

  // The run being handed out: written before `generation` is raised.
  Job job = nullptr;
  void* fn = nullptr;
  int members = 1;
  Barrier barrier;
  std::atomic<long> generation{0};
  std::atomic<bool> stopping{false};
  std::mutex start_mutex;
  std::condition_variable start_cv;

  // Workers that have not yet finished with the run (every worker counts,
  // members or not: the next run's fields are written only after all of
  // them have read this one's).
  std::atomic<int> pending{0};
  std::mutex done_mutex;
  std::condition_variable done_cv;

  std::mutex failure_mutex;
  std::exception_ptr failure;

  void record(std::exception_ptr e) {
    const std::lock_guard<std::mutex> lock(failure_mutex);
    if (!failure) failure = std::move(e);
  }

  void work(int member) {
    long seen = 0;
    for (;;) {
      wait_until(start_mutex, start_cv, [&] {
        return generation.load(std::memory_order_acquire) != seen || stopping.load();
      });
      if (stopping.load()) return;
      seen = generation.load(std::memory_order_acquire);
      if (member < members) {
        const Membership membership(&barrier);
        try {
          job(fn, member, members);
        } catch (...) {
          record(std::current_exception());
        }
      }
      if (pending.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        const std::lock_guard<std::mutex> lock(done_mutex);
        done_cv.notify_all();
      }
    }
  }
};

ThreadTeam::ThreadTeam() : impl_(new Impl) {}

ThreadTeam::~ThreadTeam() {
  {
    const std::lock_guard<std::mutex> lock(impl_->start_mutex);
    impl_->stopping.store(true);
  }
  impl_->start_cv.notify_all();
  for (std::thread& t : impl_->workers) t.join();
  delete impl_;
}

ThreadTeam& ThreadTeam::shared() {
  // Never destroyed: its workers sleep until the process ends, and no exit
  // path waits for them.
  static ThreadTeam* const team = new ThreadTeam;
  return *team;
}

void ThreadTeam::barrier() {
  if (run_barrier) run_barrier->arrive();
}

void ThreadTeam::run_erased(int members, Job job, void* fn) {
  Impl& t = *impl_;
  std::unique_lock<std::mutex> run_lock(t.run_mutex, std::defer_lock);
  if (members <= 1 || in_run || !run_lock.try_lock()) {
    const Membership alone(nullptr);
    job(fn, 0, 1);
    return;
  }
  while (static_cast<int>(t.workers.size()) < members - 1) {
    const int member = static_cast<int>(t.workers.size()) + 1;
    t.workers.emplace_back([&t, member] { t.work(member); });
  }
  t.job = job;
  t.fn = fn;
  t.members = members;
  t.barrier.reset(members);
  t.failure = nullptr;
  t.pending.store(static_cast<int>(t.workers.size()), std::memory_order_relaxed);
  {
    const std::lock_guard<std::mutex> lock(t.start_mutex);
    t.generation.fetch_add(1, std::memory_order_release);
  }
  t.start_cv.notify_all();
  {
    const Membership membership(&t.barrier);
    try {
      job(fn, 0, members);
    } catch (...) {
      t.record(std::current_exception());
    }
  }
  wait_until(t.done_mutex, t.done_cv,
             [&] { return t.pending.load(std::memory_order_acquire) == 0; });
  if (t.failure) std::rethrow_exception(t.failure);
}

int assembly_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

}  // namespace xshell
