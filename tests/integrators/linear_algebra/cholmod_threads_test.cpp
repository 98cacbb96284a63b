#include "integrators/linear_algebra/cholmod_threads.hpp"

#include <doctest/doctest.h>
#include <omp.h>

#include <random>
#include <thread>

#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell::test {

using xshell::CholeskySolver;
using xshell::CholmodThreads;
using xshell::FactorizationStatus;
using xshell::kCholmodTeamSize;

namespace {

// Threads of a parallel region opened here.
int team_size() {
  int size = 0;
#pragma omp parallel
  {
#pragma omp single
    size = omp_get_num_threads();
  }
  return size;
}

// Sets the thread count for the scope, and restores it.
struct ThreadCount {
  int before = omp_get_max_threads();
  explicit ThreadCount(int n) { omp_set_num_threads(n); }
  ~ThreadCount() { omp_set_num_threads(before); }
};

}  // namespace

TEST_CASE("A CHOLMOD call runs on one thread when the program allows fewer than CHOLMOD's teams") {
  const ThreadCount two(2);
  const int levels = omp_get_max_active_levels();
  {
    const CholmodThreads outer;
    CHECK(outer.serial());
    CHECK(omp_get_max_active_levels() == 0);
    CHECK(omp_get_max_threads() == 1);
    CHECK(team_size() == 1);
    {
      const CholmodThreads inner;  // nested: still serial, and restores only its own count
      CHECK(inner.serial());
      CHECK(team_size() == 1);
    }
    CHECK(omp_get_max_active_levels() == 0);
    CHECK(team_size() == 1);
  }
  CHECK(omp_get_max_active_levels() == levels);
  CHECK(omp_get_max_threads() == 2);
}

// Nesting level inside a parallel region opened here (0: no team was made).
int region_level() {
  int level = -1;
#pragma omp parallel num_threads(kCholmodTeamSize)
  {
#pragma omp single
    level = omp_get_level();
  }
  return level;
}

TEST_CASE("Under a serial guard a parallel region is a plain call, on this thread only") {
  // CHOLMOD opens thousands of regions per factorization; an inactive one
  // still builds a team and ends it with a system call.
  const ThreadCount two(2);
  CHECK(region_level() == 1);  // elsewhere libgomp makes the team
  {
    const CholmodThreads threads;
    REQUIRE(threads.serial());
    CHECK(region_level() == 0);
    int other_thread_level = -1;
    std::thread([&] { other_thread_level = region_level(); }).join();
    CHECK(other_thread_level == 1);  // another thread's regions are its own
    {
      const CholmodThreads nested;
      CHECK(region_level() == 0);
    }
    CHECK(region_level() == 0);  // the outer guard still holds
  }
  CHECK(region_level() == 1);
}

TEST_CASE("With as many threads as CHOLMOD's teams, a CHOLMOD call is left alone") {
  const ThreadCount enough(kCholmodTeamSize);
  const int levels = omp_get_max_active_levels();
  const CholmodThreads threads;
  CHECK_FALSE(threads.serial());
  CHECK(omp_get_max_active_levels() == levels);
  CHECK(omp_get_max_threads() == kCholmodTeamSize);
}

TEST_CASE("A factorization with dense supernodes completes on 2 threads and solves") {
  // Large dense blocks make the BLAS split its Cholesky over threads: with
  // its teams made inactive but its thread count left at 2, it would wait
  // forever for the second member.
  const ThreadCount two(2);
  const int n = 900;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd B(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) B(i, j) = value(rng);
  const Eigen::MatrixXd dense = B.transpose() * B + n * Eigen::MatrixXd::Identity(n, n);
  const Eigen::SparseMatrix<double> A = dense.sparseView();
  CholeskySolver solver;
  REQUIRE(solver.factorize(A) == FactorizationStatus::PositiveDefinite);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  const Eigen::VectorXd b = dense * x;
  CHECK((solver.solve(b) - x).norm() < 1e-10 * x.norm());
  CHECK(omp_get_max_threads() == 2);
}

}  // namespace xshell::test
