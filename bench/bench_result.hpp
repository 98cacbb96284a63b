// One row of xshell_bench's table and CSV: what is measured per case, and
// the CSV line a case's child process sends back to the parent.
#pragma once

#include <cmath>
#include <string>

namespace xshell::bench {

struct BenchResult {
  std::string name, kind;
  int subdivisions = 0, gravity = 0, threads = 1;
  long unknowns = 0, free_unknowns = 0, hessian_nonzeros = 0;
  double energy_gradient_ms = NAN, hessian_ms = NAN, factorization_ms = NAN;
  double iteration_ms = NAN, factorizations_per_iteration = NAN,
         iteration_over_factorizations = NAN;
  // The same in process CPU time (all threads): with one thread, what the
  // wall times would be on an idle machine.
  double hessian_cpu_ms = NAN, factorization_cpu_ms = NAN, iteration_cpu_ms = NAN,
         iteration_over_factorizations_cpu = NAN;
  long iterations = -1;
  double solve_s = NAN, gradient_measure = NAN;
  std::string status = "skipped";
  double peak_rss_mb = NAN;  // through the Newton relaxation (before the deployment step)
  // --solvers: the same relaxation by damped dynamics and kinetic damping;
  // dynamics_s is the median of repeated runs, alternating with Newton
  // solves whose median is newton_median_s (the ratio's denominator).
  long dynamics_steps = -1, kinetic_iterations = -1;
  double dynamics_s = NAN, kinetic_s = NAN, newton_median_s = NAN;
  std::string dynamics_status = "skipped", kinetic_status = "skipped";
  // Those Newton solves may take up to 5000 iterations (the solve above
  // stops at 100), so that a hard case still gives a ratio: their
  // iterations and status (a ratio to a failed solve means nothing).
  long comparison_newton_iterations = -1;
  std::string comparison_newton_status = "skipped";
  // Inside the solve, medians over its iterations: Hessian assembly, the
  // numeric factorizations, and everything else (evaluations, line search,
  // solves, rebase, bookkeeping).
  double solve_hessian_ms = NAN, solve_factorization_ms = NAN, solve_rest_ms = NAN;
  // Hessian assembly on one thread, timed in the same process alternately
  // with hessian_ms's thread count (the speedup is their ratio of medians).
  double hessian_1thread_ms = NAN, hessian_speedup = NAN;
  // The solve's iterations over the factorizations they performed, both as
  // timed inside the solve (cold caches and all).
  double iteration_over_solve_factorizations = NAN;
  // Hessian assembly on one thread pinned to each core in turn (the first
  // `threads` cores the process may use, warm caches): the slowest and
  // fastest, and the speedup over the fastest core that perfect balance
  // over all of them would give, sum_c t_fastest / t_c. A virtual
  // machine's cores need not be equally fast: with one at 0.8 of the
  // other's speed, 2 threads are at most 1.8x faster than the faster core.
  double hessian_slowest_core_ms = NAN, hessian_fastest_core_ms = NAN,
         hessian_speedup_ceiling = NAN;
  // One deployment step from the relaxed state: the average opening angle
  // raised by kDeploymentStep radians, solved by constrained Newton to the
  // same tolerance (deployment.hpp; the step's own iterations and time).
  long deployment_iterations = -1;
  double deployment_s = NAN;
  std::string deployment_status = "skipped";
  double deployment_peak_rss_mb = NAN;  // through the deployment step too
};

// The opening of the benchmark's deployment step, radians (the reference
// implementation's designs deploy by about this much per step).
constexpr double kDeploymentStep = 0.02;

// The CSV header, and a result as one line of it (without newline).
std::string csv_header();
std::string to_csv(const BenchResult& r);
// The result of a CSV line; status "failed" when the line does not parse.
BenchResult from_csv(const std::string& line);

}  // namespace xshell::bench
