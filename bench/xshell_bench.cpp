// xshell_bench: the cost of a Newton iteration on real and generated
// linkages, next to the cost of the sparse Cholesky factorization it needs.
//
// For every case (a graph of ../shared/data/elasticrods at subdivisions 8
// and 10, and regular grids of growing size, without and with gravity) it
// builds the statics problem of a relaxation from the flat input with
// "rest_shape": "straight" (millimetres, E = 20000, nu = 0.3, rectangle
// 10 x 7, no supports: the default pin) and measures, as medians of
// repeated runs:
//   energy + gradient, Hessian assembly, one numeric factorization
//   (CholeskySolver, symbolic analysis reused), the whole Newton iteration
//   (median over the iterations of a solve, from NewtonReport::seconds),
// and the solve itself (Newton to gradient tolerance 1e-6): iterations and
// time. The bundled samples (samples/*.obj) are relaxed instead with the
// settings of samples/grid_gravity.json (SI units, gravity, a point load,
// four supports). With --solvers, the same relaxation also by damped
// dynamics (IDA, second order, the defaults of `xshell relax --solver
// dynamics`) and by kinetic damping (at most --kinetic-limit iterations): steps or
// iterations, wall time, and the ratio to Newton's (Newton here allowed
// 5000 iterations; a ratio only when both converged). Each case runs in a
// child process, so that its peak memory (getrusage) is its own.
//
//   xshell_bench [--quick] [--reps N] [--graphs all|none|NAME,...] [--subdivisions 8,10]
//                [--grids 4,8,14,25,44] [--no-solve] [--solvers] [--kinetic-limit N]
//                [--samples all|none] [--csv FILE] [--data DIR]
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "bench_cases.hpp"
#include "bench_measure.hpp"
#include "bench_report.hpp"
#include "bench_result.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/deployment.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/kinetic_damping/kinetic_damping.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/newton/newton.hpp"
#include "linkage/statics_problem.hpp"

namespace {

using namespace xshell;
using namespace xshell::bench;

// What run_case measures besides the factorization costs.
struct BenchSettings {
  int reps = 5;
  bool solve = true;
  bool solvers = false;
  long kinetic_limit = 200000;
};

// Median time of one numeric factorization of the free Hessian at the
// start. An indefinite Hessian stops LL^T early: it is shifted as Newton
// would shift it, so that the factorization timed is complete.
double factorization_ms(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass, int reps,
                        double* cpu_ms) {
  CholeskySolver solver;
  Eigen::VectorXd shift;
  const Eigen::VectorXd* shift_ptr = nullptr;
  if (solver.factorize(H) != FactorizationStatus::PositiveDefinite) {
    const double scale = H.norm() / mass.norm();
    for (double tau = 1e-8; tau < 1e8; tau *= 4.0) {
      shift = (tau * scale) * mass;
      if (solver.factorize(H, &shift) == FactorizationStatus::PositiveDefinite) break;
    }
    shift_ptr = &shift;
  }
  return median_ms(
      reps, [&] { solver.factorize(H, shift_ptr); }, cpu_ms);
}

// The relaxation of case c by damped dynamics and by kinetic damping, each
// from the flat start, to Newton's tolerance. Dynamics runs settings.reps
// times, alternating with Newton solves: the ratio of their medians is
// less exposed to the machine's load changing between them.
void run_other_solvers(const BenchCase& c, const BenchSettings& settings, BenchResult& r) {
  std::vector<double> newton_s, dynamics_s;
  for (int k = 0; k < settings.reps; ++k) {
    {
      LinkageProblem problem = make_problem(c);
      LinkageObjective objective(problem);
      NewtonOptions options;
      options.gradient_tolerance = 1e-6;
      options.max_iterations = 5000;
      const NewtonResult result = solve_newton(objective, options);
      newton_s.push_back(result.seconds);
      r.comparison_newton_iterations = result.iterations;
      r.comparison_newton_status = result.converged() ? "converged" : "failed";
    }
    LinkageProblem problem = make_problem(c);
    LinkageObjective objective(problem);
    DynamicsOptions options;
    options.stopping.gradient_tolerance = 1e-6;
    options.stopping.max_steps = 20000;
    const DynamicsResult result = solve_dynamics(objective, options);
    r.dynamics_steps = result.iterations;
    dynamics_s.push_back(result.seconds);
    r.dynamics_status = result.converged() ? "converged" : "failed";
  }
  r.newton_median_s = median(newton_s);
  r.dynamics_s = median(dynamics_s);
  {
    LinkageProblem problem = make_problem(c);
    LinkageObjective objective(problem);
    KineticDampingOptions options;
    options.gradient_tolerance = 1e-6;
    options.max_iterations = settings.kinetic_limit;
    const KineticDampingResult result = solve_kinetic_damping(objective, options);
    r.kinetic_iterations = result.iterations;
    r.kinetic_s = result.seconds;
    r.kinetic_status = result.converged() ? "converged" : "failed";
  }
}

// One deployment step from the problem's (relaxed) state, into r.
void deployment_step(LinkageProblem& problem, BenchResult& r) {
  DeploymentPlan plan;
  plan.average_angle = average_opening_angle(problem.linkage()) + kDeploymentStep;
  plan.steps = 1;
  DeploymentOptions options;
  options.newton.gradient_tolerance = 1e-6;
  DeploymentResult result;
  try {
    result = deploy(problem, plan, options);
  } catch (const std::invalid_argument&) {  // every opening angle fixed
    r.deployment_status = "not_applicable";
    return;
  }
  r.deployment_status = "failed";
  if (!result.converged())
    std::fprintf(stderr, "%s, n_s %d: deployment step %s: %s\n", r.name.c_str(), r.subdivisions,
                 describe(result.status), result.reason.c_str());
  if (result.steps.size() < 2) return;  // step 0 is the start's own solve
  const DeploymentStep& step = result.steps.back();
  r.deployment_iterations = step.iterations;
  r.deployment_s = step.seconds;
  if (result.converged()) r.deployment_status = step.stable ? "converged" : "converged_unstable";
}

// The Hessian's assembly on 1 thread against all, and on each core alone
// (the slowest and fastest, and the speed-up they allow), into r.
template <class Assemble>
void measure_hessian_threads(const Assemble& assemble_hessian, int reps, BenchResult& r) {
#ifdef _OPENMP
  if (r.threads < 2) return;
  const std::vector<int> cores = allowed_cores(r.threads);
  // One thread pinned to each core in turn, after an untimed call that
  // brings the data into that core's cache; then, apart from these (a
  // worker idle for several calls falls asleep, and waking it costs the
  // next parallel call), 1 thread and all alternately.
  std::vector<std::vector<double>> on_core(cores.size());
  omp_set_num_threads(1);
  for (int i = 0; i < reps; ++i)
    for (size_t c = 0; c < cores.size(); ++c) {
      PinnedThread pin(cores[c]);
      assemble_hessian();
      on_core[c].push_back(median_ms(1, assemble_hessian));
    }
  std::vector<double> one, all;
  omp_set_num_threads(r.threads);
  assemble_hessian();
  for (int i = 0; i < reps; ++i) {
    omp_set_num_threads(1);
    one.push_back(median_ms(1, assemble_hessian));
    omp_set_num_threads(r.threads);
    all.push_back(median_ms(1, assemble_hessian));
  }
  r.hessian_1thread_ms = median(one);
  r.hessian_speedup = median(one) / median(all);
  if (cores.size() != static_cast<size_t>(r.threads)) return;
  std::vector<double> ms;
  for (const std::vector<double>& t : on_core) ms.push_back(median(t));
  r.hessian_slowest_core_ms = *std::max_element(ms.begin(), ms.end());
  r.hessian_fastest_core_ms = *std::min_element(ms.begin(), ms.end());
  r.hessian_speedup_ceiling = 0.0;
  for (double t : ms) r.hessian_speedup_ceiling += r.hessian_fastest_core_ms / t;
#else
  (void)assemble_hessian;
  (void)reps;
  (void)r;
#endif
}

// Energy + gradient, Hessian assembly (also on 1 thread and on each core
// alone) and one factorization of the free Hessian at the start, into r.
void measure_assembly(LinkageProblem& problem, int reps, BenchResult& r) {
  double sink = 0.0;
  // The problem caches its derivatives until the configuration changes:
  // every timed call starts without them.
  r.energy_gradient_ms = median_ms(reps, [&] {
    problem.discard_cached_derivatives();
    sink += problem.energy().total();
    sink += problem.free_gradient()[0];
  });
  const auto assemble_hessian = [&] {
    problem.discard_cached_derivatives();
    sink += problem.free_hessian().valuePtr()[0];
  };
  r.hessian_ms = median_ms(reps, assemble_hessian, &r.hessian_cpu_ms);
  measure_hessian_threads(assemble_hessian, reps, r);
  const Eigen::SparseMatrix<double> H = problem.free_hessian();
  r.hessian_nonzeros = H.nonZeros();
  r.factorization_ms = factorization_ms(H, problem.free_mass(), reps, &r.factorization_cpu_ms);
  if (!std::isfinite(sink)) std::fprintf(stderr, "non-finite energy\n");
}

// Newton's relaxation of the problem from its start, timed per iteration
// (medians of the iterations' own times, and the ratios to the
// factorizations they perform), into r.
NewtonResult measure_newton(LinkageProblem& problem, BenchResult& r) {
  LinkageObjective objective(problem);
  NewtonOptions options;
  options.gradient_tolerance = 1e-6;
  NewtonSolver solver(objective, options);
  std::vector<double> seconds, cpu, hessian_s, factorization_s, rest_s;
  long factorizations = 0;
  double total = 0.0, total_cpu = 0.0, last_cpu = 0.0, total_factorization = 0.0;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport& report) {
    const double now = cpu_seconds();
    if (report.iteration > 0) {
      seconds.push_back(report.seconds);
      hessian_s.push_back(report.hessian_seconds);
      factorization_s.push_back(report.factorization_seconds);
      rest_s.push_back(report.seconds - report.hessian_seconds - report.factorization_seconds);
      cpu.push_back(now - last_cpu);  // includes the driver's bookkeeping between reports
      total += report.seconds;
      total_factorization += report.factorization_seconds;
      total_cpu += now - last_cpu;
      factorizations += report.factorizations;
    }
    last_cpu = now;
  };
  const NewtonResult result = solver.solve(callbacks);
  r.iterations = result.iterations;
  r.solve_s = result.seconds;
  r.gradient_measure = result.gradient_measure;
  r.status = result.converged() ? (result.stable ? "converged" : "converged_unstable") : "failed";
  if (seconds.empty()) return result;
  r.iteration_ms = 1e3 * median(seconds);
  r.solve_hessian_ms = 1e3 * median(hessian_s);
  r.solve_factorization_ms = 1e3 * median(factorization_s);
  r.solve_rest_ms = 1e3 * median(rest_s);
  r.factorizations_per_iteration = double(factorizations) / double(seconds.size());
  r.iteration_over_factorizations = 1e3 * total / (double(factorizations) * r.factorization_ms);
  r.iteration_over_solve_factorizations = total / total_factorization;
  r.iteration_cpu_ms = 1e3 * median(cpu);
  r.iteration_over_factorizations_cpu =
      1e3 * total_cpu / (double(factorizations) * r.factorization_cpu_ms);
  return result;
}

BenchResult run_case(const BenchCase& c, const BenchSettings& settings) {
  BenchResult r;
  r.name = c.name;
  r.kind = c.kind;
  r.subdivisions = c.subdivisions;
  r.gravity = c.gravity;
#ifdef _OPENMP
  r.threads = omp_get_max_threads();
#endif
  LinkageProblem problem = make_problem(c);
  r.unknowns = problem.linkage().num_dofs();
  r.free_unknowns = problem.num_free();
  measure_assembly(problem, settings.reps, r);
  if (!settings.solve) {
    r.status = "not_solved";
    r.peak_rss_mb = peak_rss_mb();
    return r;
  }
  const NewtonResult result = measure_newton(problem, r);
  r.peak_rss_mb = peak_rss_mb();
  if (result.converged()) {
    deployment_step(problem, r);
    r.deployment_peak_rss_mb = peak_rss_mb();
  }
  if (settings.solvers) run_other_solvers(c, settings, r);
  return r;
}

// Runs one case in a child process; its result comes back as a CSV line.
BenchResult run_isolated(const BenchCase& c, const BenchSettings& settings) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(fd[0]);
    std::string line;
    try {
      line = to_csv(run_case(c, settings)) + "\n";
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", c.name.c_str(), e.what());
      line = "error\n";
    }
    const ssize_t written = write(fd[1], line.data(), line.size());
    close(fd[1]);
    _exit(written == static_cast<ssize_t>(line.size()) ? 0 : 1);
  }
  close(fd[1]);
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(fd[0], buffer, sizeof buffer)) > 0;)
    text.append(buffer, static_cast<size_t>(n));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  BenchResult r = from_csv(text.substr(0, text.find('\n')));
  if (r.name.empty()) {
    r.name = c.name;
    r.kind = c.kind;
    r.subdivisions = c.subdivisions;
    r.gravity = c.gravity;
    r.status = "failed";
  }
  return r;
}

// xshell_bench's command line.
struct BenchArguments {
  CaseSelection cases;
  BenchSettings settings;
  std::string csv = "xshell_bench.csv";
};

void add_options(CLI::App& app, BenchArguments& args, bool& quick, bool& no_solve) {
  app.add_flag("--quick", quick, "two small designs at subdivision 8, grids 4,8,14, 3 repetitions");
  app.add_option("--reps", args.settings.reps, "repetitions of each timing (median reported)")
      ->check(CLI::PositiveNumber);
  app.add_option("--graphs", args.cases.graphs,
                 "\"designs\" (the five architectural designs, mm), \"all\", \"none\", or names "
                 "(file stems or "
                 "prefixes), comma-separated");
  app.add_option("--subdivisions", args.cases.subdivisions,
                 "subdivisions for the graphs, comma-separated");
  app.add_option("--grids", args.cases.grids,
                 "grid sizes (crossings per side), comma-separated; empty for none");
  app.add_flag("--no-solve", no_solve, "skip the Newton solves");
  app.add_flag("--solvers", args.settings.solvers,
               "also relax by damped dynamics and kinetic damping, with ratios to Newton");
  app.add_option("--kinetic-limit", args.settings.kinetic_limit,
                 "iteration limit of kinetic damping")
      ->check(CLI::PositiveNumber);
  app.add_option("--samples", args.cases.samples,
                 "\"all\": the bundled samples (samples/*.obj) with samples/grid_gravity.json's "
                 "settings; \"none\"")
      ->check(CLI::IsMember({"all", "none"}));
  app.add_option("--csv", args.csv, "CSV file to write");
  app.add_option("--data", args.cases.data, "folder of the real linkage graphs");
}

// --quick's smaller defaults for the options not given.
void apply_quick(const CLI::App& app, BenchArguments& args) {
  args.settings.reps = std::min(args.settings.reps, 3);
  if (app.count("--graphs") == 0) args.cases.graphs = "manta_ray,darth_vader";
  if (app.count("--subdivisions") == 0) args.cases.subdivisions = "8";
  if (app.count("--grids") == 0) args.cases.grids = "4,8,14";
}

void print_header(size_t cases, int reps) {
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  std::printf(
      "xshell_bench: %zu cases, %d repetitions, %d threads (OMP_WAIT_POLICY=%s); times in ms "
      "(solve in s), "
      "medians; H1/Hn: Hessian on 1 thread / on all threads (same process, alternating); rest: "
      "iteration minus its Hessian and "
      "factorizations; it/f: iteration / its factorizations (wall; factorization timed alone), "
      "it/fs: the same with "
      "the factorizations as timed inside the solve, cpu: it/f in CPU time\n",
      cases, reps, threads,
      std::getenv("OMP_WAIT_POLICY") != nullptr ? std::getenv("OMP_WAIT_POLICY") : "default");
  std::printf("BLAS: %s\n", loaded_blas().c_str());
  print_row_header();
}

}  // namespace

int main(int argc, char** argv) {
  // The OpenMP wait policy is left as the program's users get it (libgomp's
  // default: spin a while, then sleep). Forcing PASSIVE, as this program
  // once did, made every barrier a sleep and a wake-up: energy + gradient on
  // 2 threads 2-4x slower than on 1 below 10^4 unknowns.
  CLI::App app{"xshell_bench: cost of Newton iterations, assembly and factorization"};
  BenchArguments args;
  args.cases.source_dir = XSHELL_SOURCE_DIR;
  args.cases.data = std::string(XSHELL_SOURCE_DIR) + "/../shared/data/elasticrods";
  bool quick = false, no_solve = false;
  add_options(app, args, quick, no_solve);
  CLI11_PARSE(app, argc, argv);
  if (quick) apply_quick(app, args);
  args.settings.solve = !no_solve;

  const std::vector<BenchCase> cases = collect_cases(args.cases);
  print_header(cases.size(), args.settings.reps);
  std::ofstream out(args.csv);
  out << csv_header() << "\n";
  std::vector<BenchResult> results;
  for (const BenchCase& c : cases) {
    BenchResult r = run_isolated(c, args.settings);
    print_row(r);
    out << to_csv(r) << "\n";
    out.flush();
    results.push_back(r);
  }

  print_grid_slopes(results);
  if (args.settings.solvers && args.settings.solve) print_solver_comparison(results);
  std::printf("wrote %s\n", args.csv.c_str());
  return 0;
}
