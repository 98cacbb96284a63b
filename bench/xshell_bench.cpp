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
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

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
#include "io/config.hpp"
#include "io/input_error.hpp"
#include "io/obj_reader.hpp"
#include "io/problem_setup.hpp"
#include "linkage/statics_problem.hpp"

namespace {

using namespace xshell;
using namespace xshell::bench;
namespace fs = std::filesystem;

struct BenchCase {
  std::string name;
  std::string kind;  // "graph", "grid" or "sample"
  LineGraph graph;
  int subdivisions = 8;
  bool gravity = false;
  std::shared_ptr<const ProblemSetup>
      setup;  // a sample's, from its configuration; else the fields above
};

// What run_case measures besides the factorization costs.
struct BenchSettings {
  int reps = 5;
  bool solve = true;
  bool solvers = false;
  long kinetic_limit = 200000;
};

// A regular grid of n x n crossings of straight rods (spacing 100 mm), each
// rod running half a spacing past its last crossing to a free end, with the
// crossings moved in the plane by up to 8 mm so that the rods are kinked at
// the joints: relaxing it from flat with straight rest shapes has work to do.
LineGraph wavy_grid(int n) {
  const double spacing = 100.0, amplitude = 8.0;
  LineGraph g;
  auto joint = [&](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = spacing * j, y = spacing * i;
      g.vertices.emplace_back(x + amplitude * std::sin(1.3 * i + 0.7 * j),
                              y + amplitude * std::cos(0.9 * i - 1.1 * j), 0.0);
    }
  auto free_end = [&](double x, double y) {
    g.vertices.emplace_back(x, y, 0.0);
    return static_cast<int>(g.vertices.size()) - 1;
  };
  for (int i = 0; i < n; ++i) {  // rods along x, then along y
    g.edges.push_back({free_end(-0.5 * spacing, spacing * i), joint(i, 0)});
    for (int j = 0; j + 1 < n; ++j) g.edges.push_back({joint(i, j), joint(i, j + 1)});
    g.edges.push_back({joint(i, n - 1), free_end(spacing * (n - 0.5), spacing * i)});
  }
  for (int j = 0; j < n; ++j) {
    g.edges.push_back({free_end(spacing * j, -0.5 * spacing), joint(0, j)});
    for (int i = 0; i + 1 < n; ++i) g.edges.push_back({joint(i, j), joint(i + 1, j)});
    g.edges.push_back({joint(n - 1, j), free_end(spacing * j, spacing * (n - 0.5))});
  }
  return g;
}

LinkageProblem make_problem(const BenchCase& c) {
  if (c.setup)
    return LinkageProblem(RodLinkage(c.setup->graph, c.setup->options), c.setup->statics);
  LineGraph graph = c.graph;
  Eigen::Vector3d lo = graph.vertices.at(0), hi = lo;
  for (const auto& v : graph.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  for (auto& v : graph.vertices) v -= 0.5 * (lo + hi);  // as the configuration reader does
  LinkageOptions options;
  options.subdivisions = c.subdivisions;
  options.rest_shape = RestShape::Straight;
  options.material.young_modulus = 20000.0;  // N/mm^2
  options.material.poisson_ratio = 0.3;
  options.material.density = c.gravity ? 1.0e-9 : 0.0;  // t/mm^3 (1000 kg/m^3)
  options.material.section = {SectionShape::Rectangle, 10.0, 7.0};
  StaticsSetup setup;
  if (c.gravity) setup.gravity = Eigen::Vector3d(0.0, 0.0, -9810.0);  // mm/s^2
  return LinkageProblem(RodLinkage(graph, options), setup);
}

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

BenchResult run_case(const BenchCase& c, const BenchSettings& settings) {
  const int reps = settings.reps;
  const bool solve = settings.solve;
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
#ifdef _OPENMP
  if (r.threads > 1) {
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
    if (cores.size() == static_cast<size_t>(r.threads)) {
      std::vector<double> ms;
      for (const std::vector<double>& t : on_core) ms.push_back(median(t));
      r.hessian_slowest_core_ms = *std::max_element(ms.begin(), ms.end());
      r.hessian_fastest_core_ms = *std::min_element(ms.begin(), ms.end());
      r.hessian_speedup_ceiling = 0.0;
      for (double t : ms) r.hessian_speedup_ceiling += r.hessian_fastest_core_ms / t;
    }
  }
#endif
  const Eigen::SparseMatrix<double> H = problem.free_hessian();
  r.hessian_nonzeros = H.nonZeros();
  r.factorization_ms = factorization_ms(H, problem.free_mass(), reps, &r.factorization_cpu_ms);
  if (!std::isfinite(sink)) std::fprintf(stderr, "non-finite energy\n");

  if (solve) {
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
    if (!seconds.empty()) {
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
    }
    r.peak_rss_mb = peak_rss_mb();
    if (result.converged()) {
      deployment_step(problem, r);
      r.deployment_peak_rss_mb = peak_rss_mb();
    }
    if (settings.solvers) run_other_solvers(c, settings, r);
  } else {
    r.status = "not_solved";
    r.peak_rss_mb = peak_rss_mb();
  }
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

std::vector<int> parse_ints(const std::string& text) {
  std::vector<int> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(std::stoi(item));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  // The OpenMP wait policy is left as the program's users get it (libgomp's
  // default: spin a while, then sleep). Forcing PASSIVE, as this program
  // once did, made every barrier a sleep and a wake-up: energy + gradient on
  // 2 threads 2-4x slower than on 1 below 10^4 unknowns.
  CLI::App app{"xshell_bench: cost of Newton iterations, assembly and factorization"};
  bool quick = false, no_solve = false, solvers = false;
  long kinetic_limit = 200000;
  int reps = 5;
  std::string graphs = "designs", subdivisions = "8,10", grids = "4,8,14,25,44",
              csv = "xshell_bench.csv";
  std::string data = std::string(XSHELL_SOURCE_DIR) + "/../shared/data/elasticrods";
  std::string samples = "all";
  app.add_flag("--quick", quick, "two small designs at subdivision 8, grids 4,8,14, 3 repetitions");
  app.add_option("--reps", reps, "repetitions of each timing (median reported)")
      ->check(CLI::PositiveNumber);
  app.add_option("--graphs", graphs,
                 "\"designs\" (the five architectural designs, mm), \"all\", \"none\", or names "
                 "(file stems or "
                 "prefixes), comma-separated");
  app.add_option("--subdivisions", subdivisions, "subdivisions for the graphs, comma-separated");
  app.add_option("--grids", grids,
                 "grid sizes (crossings per side), comma-separated; empty for none");
  app.add_flag("--no-solve", no_solve, "skip the Newton solves");
  app.add_flag("--solvers", solvers,
               "also relax by damped dynamics and kinetic damping, with ratios to Newton");
  app.add_option("--kinetic-limit", kinetic_limit, "iteration limit of kinetic damping")
      ->check(CLI::PositiveNumber);
  app.add_option("--samples", samples,
                 "\"all\": the bundled samples (samples/*.obj) with samples/grid_gravity.json's "
                 "settings; \"none\"")
      ->check(CLI::IsMember({"all", "none"}));
  app.add_option("--csv", csv, "CSV file to write");
  app.add_option("--data", data, "folder of the real linkage graphs");
  CLI11_PARSE(app, argc, argv);
  if (quick) {
    reps = std::min(reps, 3);
    if (app.count("--graphs") == 0) graphs = "manta_ray,darth_vader";
    if (app.count("--subdivisions") == 0) subdivisions = "8";
    if (app.count("--grids") == 0) grids = "4,8,14";
  }

  std::vector<BenchCase> cases;
  // The bundled sample's configuration: material, supports, loads and
  // subdivisions of the samples and of the small shared graphs.
  const Config sample_config =
      read_config((fs::path(XSHELL_SOURCE_DIR) / "samples" / "grid_gravity.json").string());
  const std::vector<std::string> designs = {"manta_ray", "darth_vader", "scary_face", "hourglass",
                                            "large"};
  if (graphs != "none") {
    std::vector<std::string> wanted;
    if (graphs == "designs") wanted = designs;
    if (graphs != "designs" && graphs != "all") {
      std::stringstream in(graphs);
      for (std::string item; std::getline(in, item, ',');) wanted.push_back(item);
    }
    if (!fs::is_directory(data)) {
      std::printf("graphs skipped: %s is absent\n", data.c_str());
    } else {
      std::vector<fs::path> files;
      for (const auto& entry : fs::directory_iterator(data))
        if (entry.path().extension() == ".obj") files.push_back(entry.path());
      std::vector<std::pair<size_t, fs::path>> chosen;
      for (const auto& path : files) {
        const std::string stem = path.stem().string();
        if (graphs == "all") chosen.emplace_back(0, path);
        for (size_t k = 0; k < wanted.size(); ++k)
          if (stem.rfind(wanted[k], 0) == 0) chosen.emplace_back(k, path);
      }
      std::sort(chosen.begin(), chosen.end());
      for (int n : parse_ints(subdivisions))
        for (const auto& [order, path] : chosen) {
          BenchCase c;
          c.name = path.stem().string().substr(0, 24);
          c.kind = "graph";
          c.graph = read_obj(path.string());
          c.subdivisions = n;
          const bool design = std::any_of(
              designs.begin(), designs.end(),
              [&](const std::string& d) { return path.stem().string().rfind(d, 0) == 0; });
          if (!design) {
            // The small graphs are of order 1, not millimetres: the samples'
            // laths (metres), their input shape as rest shape, gravity and
            // the four corners pinned, as the validation runs use them.
            Config config = sample_config;
            config.subdivisions = n;
            config.rest_shape = RestShape::Input;
            config.supports.clear();
            for (int v : corner_vertices(c.graph))
              config.supports.push_back({v, {Fixed::Position}});
            config.loads.forces.clear();
            c.setup = std::make_shared<const ProblemSetup>(make_problem_setup(config, c.graph));
            c.gravity = c.setup->statics.gravity.squaredNorm() > 0.0;
          }
          cases.push_back(c);
        }
    }
  }
  if (samples == "all") {
    // Each sample with the material, supports and loads of grid_gravity.json.
    const fs::path folder = fs::path(XSHELL_SOURCE_DIR) / "samples";
    const Config& config = sample_config;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ".obj") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const auto& path : files) {
      BenchCase c;
      c.name = "samples/" + path.stem().string();
      c.kind = "sample";
      LineGraph graph;
      try {
        graph = read_obj(path.string());
      } catch (const InputError& e) {  // a surface (a design's target), not a linkage
        std::printf("skipped %s: %s\n", c.name.c_str(), e.what());
        continue;
      }
      c.setup = std::make_shared<const ProblemSetup>(make_problem_setup(config, graph));
      c.subdivisions = c.setup->options.subdivisions;
      c.gravity = c.setup->statics.gravity.squaredNorm() > 0.0;
      cases.push_back(c);
    }
  }
  for (int n : parse_ints(grids))
    for (bool gravity : {false, true}) {
      BenchCase c;
      c.name = "grid" + std::to_string(n) + "x" + std::to_string(n);
      c.kind = "grid";
      c.graph = wavy_grid(n);
      c.subdivisions = 8;
      c.gravity = gravity;
      cases.push_back(c);
    }

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
      cases.size(), reps, threads,
      std::getenv("OMP_WAIT_POLICY") != nullptr ? std::getenv("OMP_WAIT_POLICY") : "default");
  std::printf("BLAS: %s\n", loaded_blas().c_str());
  print_row_header();
  std::ofstream out(csv);
  out << kColumns << "\n";
  std::vector<BenchResult> results;
  const BenchSettings settings{reps, !no_solve, solvers, kinetic_limit};
  for (const BenchCase& c : cases) {
    BenchResult r = run_isolated(c, settings);
    print_row(r);
    out << to_csv(r) << "\n";
    out.flush();
    results.push_back(r);
  }

  print_grid_slopes(results);
  if (solvers && !no_solve) print_solver_comparison(results);
  std::printf("wrote %s\n", csv.c_str());
  return 0;
}
