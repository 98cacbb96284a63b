// The benchmark's printed report: the per-case table, the log-log slopes
// over the generated grids, and the solvers' comparison.
#pragma once

#include <vector>

#include "bench_result.hpp"

namespace xshell::bench {

void print_row_header();
void print_row(const BenchResult& r);
// Least-squares slope of log(y) against log(x) (NaN with fewer than 2 points).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);
// Slopes over the grids without gravity: everything but the factorizations,
// and the factorization itself (nothing when fewer than 2 grids ran).
void print_grid_slopes(const std::vector<BenchResult>& results);
// Newton, damped dynamics and kinetic damping on each case (--solvers).
void print_solver_comparison(const std::vector<BenchResult>& results);

}  // namespace xshell::bench
