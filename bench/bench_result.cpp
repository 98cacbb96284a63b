#include "bench_result.hpp"

#include <cstdlib>
#include <sstream>
#include <vector>

namespace xshell::bench {

const char* kColumns =
    "case,kind,subdivisions,gravity,threads,unknowns,free_unknowns,hessian_nonzeros,energy_"
    "gradient_ms,"
    "hessian_ms,factorization_ms,iteration_ms,factorizations_per_iteration,iteration_over_"
    "factorizations,"
    "newton_iterations,solve_s,status,gradient_measure,peak_rss_mb,hessian_cpu_ms,factorization_"
    "cpu_ms,"
    "iteration_cpu_ms,iteration_over_factorizations_cpu,dynamics_steps,dynamics_s,dynamics_status,"
    "kinetic_iterations,kinetic_s,kinetic_status,solve_hessian_ms,solve_factorization_ms,solve_"
    "rest_ms,"
    "hessian_1thread_ms,hessian_speedup,iteration_over_solve_factorizations,newton_median_s,"
    "comparison_newton_iterations,comparison_newton_status,hessian_slowest_core_ms,hessian_fastest_"
    "core_ms,"
    "hessian_speedup_ceiling,deployment_iterations,deployment_s,deployment_status,deployment_peak_"
    "rss_mb";

std::string to_csv(const BenchResult& r) {
  std::ostringstream o;
  o.precision(6);
  o << r.name << ',' << r.kind << ',' << r.subdivisions << ',' << r.gravity << ',' << r.threads
    << ',' << r.unknowns << ',' << r.free_unknowns << ',' << r.hessian_nonzeros << ','
    << r.energy_gradient_ms << ',' << r.hessian_ms << ',' << r.factorization_ms << ','
    << r.iteration_ms << ',' << r.factorizations_per_iteration << ','
    << r.iteration_over_factorizations << ',' << r.iterations << ',' << r.solve_s << ',' << r.status
    << ',' << r.gradient_measure << ',' << r.peak_rss_mb << ',' << r.hessian_cpu_ms << ','
    << r.factorization_cpu_ms << ',' << r.iteration_cpu_ms << ','
    << r.iteration_over_factorizations_cpu << ',' << r.dynamics_steps << ',' << r.dynamics_s << ','
    << r.dynamics_status << ',' << r.kinetic_iterations << ',' << r.kinetic_s << ','
    << r.kinetic_status << ',' << r.solve_hessian_ms << ',' << r.solve_factorization_ms << ','
    << r.solve_rest_ms << ',' << r.hessian_1thread_ms << ',' << r.hessian_speedup << ','
    << r.iteration_over_solve_factorizations << ',' << r.newton_median_s << ','
    << r.comparison_newton_iterations << ',' << r.comparison_newton_status << ','
    << r.hessian_slowest_core_ms << ',' << r.hessian_fastest_core_ms << ','
    << r.hessian_speedup_ceiling << ',' << r.deployment_iterations << ',' << r.deployment_s << ','
    << r.deployment_status << ',' << r.deployment_peak_rss_mb;
  return o.str();
}

BenchResult from_csv(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream in(line);
  for (std::string item; std::getline(in, item, ',');) f.push_back(item);
  BenchResult r;
  // 36: written before the comparison's Newton columns; 38: before the
  // cores' columns; 41: before the deployment step's.
  if (f.size() != 36 && f.size() != 38 && f.size() != 41 && f.size() != 45) {
    r.status = "failed";
    return r;
  }
  auto d = [](const std::string& s) { return std::strtod(s.c_str(), nullptr); };
  r.name = f[0];
  r.kind = f[1];
  r.subdivisions = std::stoi(f[2]);
  r.gravity = std::stoi(f[3]);
  r.threads = std::stoi(f[4]);
  r.unknowns = std::stol(f[5]);
  r.free_unknowns = std::stol(f[6]);
  r.hessian_nonzeros = std::stol(f[7]);
  r.energy_gradient_ms = d(f[8]);
  r.hessian_ms = d(f[9]);
  r.factorization_ms = d(f[10]);
  r.iteration_ms = d(f[11]);
  r.factorizations_per_iteration = d(f[12]);
  r.iteration_over_factorizations = d(f[13]);
  r.iterations = std::stol(f[14]);
  r.solve_s = d(f[15]);
  r.status = f[16];
  r.gradient_measure = d(f[17]);
  r.peak_rss_mb = d(f[18]);
  r.hessian_cpu_ms = d(f[19]);
  r.factorization_cpu_ms = d(f[20]);
  r.iteration_cpu_ms = d(f[21]);
  r.iteration_over_factorizations_cpu = d(f[22]);
  r.dynamics_steps = std::stol(f[23]);
  r.dynamics_s = d(f[24]);
  r.dynamics_status = f[25];
  r.kinetic_iterations = std::stol(f[26]);
  r.kinetic_s = d(f[27]);
  r.kinetic_status = f[28];
  r.solve_hessian_ms = d(f[29]);
  r.solve_factorization_ms = d(f[30]);
  r.solve_rest_ms = d(f[31]);
  r.hessian_1thread_ms = d(f[32]);
  r.hessian_speedup = d(f[33]);
  r.iteration_over_solve_factorizations = d(f[34]);
  r.newton_median_s = d(f[35]);
  if (f.size() >= 38) {
    r.comparison_newton_iterations = std::stol(f[36]);
    r.comparison_newton_status = f[37];
  }
  if (f.size() >= 41) {
    r.hessian_slowest_core_ms = d(f[38]);
    r.hessian_fastest_core_ms = d(f[39]);
    r.hessian_speedup_ceiling = d(f[40]);
  }
  if (f.size() >= 45) {
    r.deployment_iterations = std::stol(f[41]);
    r.deployment_s = d(f[42]);
    r.deployment_status = f[43];
    r.deployment_peak_rss_mb = d(f[44]);
  }
  return r;
}

}  // namespace xshell::bench
