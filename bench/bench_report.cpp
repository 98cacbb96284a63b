#include "bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace xshell::bench {

void print_row_header() {
  std::printf(
      "%-24s %3s %2s %7s %9s %9s %9s %5s %5s %9s %9s %7s %5s %6s %6s %6s %4s %8s %4s %7s %7s  %s\n",
      "case", "n_s", "g", "free", "H nnz", "E+grad", "Hessian", "H1/Hn", "ceil", "factor", "iter",
      "rest", "f/it", "it/f", "it/fs", "cpu", "its", "solve", "dep", "dep s", "MB", "status");
}

void print_row(const BenchResult& r) {
  std::printf(
      "%-24s %3d %2s %7ld %9ld %9.2f %9.2f %5.2f %5.2f %9.2f %9.2f %7.2f %5.2f %6.2f %6.2f %6.2f "
      "%4ld %8.2f %4ld %7.2f %7.0f  "
      "%s\n",
      r.name.c_str(), r.subdivisions, r.gravity ? "g" : "-", r.free_unknowns, r.hessian_nonzeros,
      r.energy_gradient_ms, r.hessian_ms, r.hessian_speedup, r.hessian_speedup_ceiling,
      r.factorization_ms, r.iteration_ms, r.solve_rest_ms, r.factorizations_per_iteration,
      r.iteration_over_factorizations, r.iteration_over_solve_factorizations,
      r.iteration_over_factorizations_cpu, r.iterations, r.solve_s, r.deployment_iterations,
      r.deployment_s, r.peak_rss_mb, r.status.c_str());
  std::fflush(stdout);
}

// Least-squares slope of log(y) against log(x).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0 && y[i] > 0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  if (n < 2) return NAN;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void print_grid_slopes(const std::vector<BenchResult>& results) {
  // Scaling over the grids without gravity: everything but the
  // factorizations, and the factorization itself.
  std::vector<double> n, outside, factor, hessian, gradient, outside_cpu, factor_cpu, hessian_cpu,
      outside_solve, factor_solve;
  for (const BenchResult& r : results) {
    if (r.kind != "grid" || r.gravity) continue;
    n.push_back(double(r.free_unknowns));
    factor.push_back(r.factorization_ms);
    hessian.push_back(r.hessian_ms);
    gradient.push_back(r.energy_gradient_ms);
    outside.push_back(r.iteration_ms - r.factorizations_per_iteration * r.factorization_ms);
    factor_cpu.push_back(r.factorization_cpu_ms);
    hessian_cpu.push_back(r.hessian_cpu_ms);
    outside_cpu.push_back(r.iteration_cpu_ms -
                          r.factorizations_per_iteration * r.factorization_cpu_ms);
    outside_solve.push_back(r.solve_hessian_ms + r.solve_rest_ms);
    factor_solve.push_back(r.solve_factorization_ms);
  }
  if (n.size() >= 2) {
    // An iteration minus its factorizations timed alone can come out
    // negative on a noisy machine (an iteration's factorizations run on a
    // warmer or quieter moment): then that slope has no meaning.
    const auto slope_text = [&](const std::vector<double>& y) {
      if (*std::min_element(y.begin(), y.end()) <= 0.0)
        return std::string("n/a (some differences <= 0)");
      char text[32];
      std::snprintf(text, sizeof text, "%.2f", loglog_slope(n, y));
      return std::string(text);
    };
    std::printf(
        "log-log slopes over the grids (%.0f to %.0f unknowns): iteration minus factorizations %s, "
        "Hessian %.2f, energy+gradient %.2f, factorization %.2f\n",
        n.front(), n.back(), slope_text(outside).c_str(), loglog_slope(n, hessian),
        loglog_slope(n, gradient), loglog_slope(n, factor));
    std::printf(
        "the same in CPU time: iteration minus factorizations %s, Hessian %.2f, factorization "
        "%.2f\n",
        slope_text(outside_cpu).c_str(), loglog_slope(n, hessian_cpu), loglog_slope(n, factor_cpu));
    std::printf(
        "timed inside the solves (medians per iteration): everything but the factorizations %.2f, "
        "the factorizations %.2f\n",
        loglog_slope(n, outside_solve), loglog_slope(n, factor_solve));
  }
}

void print_solver_comparison(const std::vector<BenchResult>& results) {
  std::printf(
      "\nthe same relaxation by each solver (tolerance 1e-6; Newton up to 5000 iterations): "
      "iterations or "
      "steps, seconds (Newton and dynamics: medians of --reps runs, alternating), ratio to Newton "
      "(n/a "
      "unless both converged)\n");
  std::printf("%-24s %3s %2s %7s | %5s %8s %-9s | %6s %8s %6s %-9s | %7s %8s %7s %s\n", "case",
              "n_s", "g", "free", "its", "newton", "", "steps", "dynamics", "ratio", "", "its",
              "kinetic", "ratio", "");
  for (const BenchResult& r : results) {
    // A ratio only between solves that both converged.
    const bool newton_ok = r.comparison_newton_status == "converged";
    auto ratio = [&](double seconds, const std::string& status) {
      char text[32] = "n/a";
      if (newton_ok && status == "converged")
        std::snprintf(text, sizeof text, "%.1f", seconds / r.newton_median_s);
      return std::string(text);
    };
    std::printf("%-24s %3d %2s %7ld | %5ld %8.3f %-9s | %6ld %8.3f %6s %-9s | %7ld %8.3f %7s %s\n",
                r.name.c_str(), r.subdivisions, r.gravity ? "g" : "-", r.free_unknowns,
                r.comparison_newton_iterations, r.newton_median_s,
                r.comparison_newton_status.c_str(), r.dynamics_steps, r.dynamics_s,
                ratio(r.dynamics_s, r.dynamics_status).c_str(), r.dynamics_status.c_str(),
                r.kinetic_iterations, r.kinetic_s, ratio(r.kinetic_s, r.kinetic_status).c_str(),
                r.kinetic_status.c_str());
  }
}

}  // namespace xshell::bench
