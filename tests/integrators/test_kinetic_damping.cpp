#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "integrators/dynamics.hpp"
#include "integrators/kinetic_damping.hpp"
#include "integrators/linkage_objective.hpp"
#include "integrators/mass_and_damping.hpp"
#include "integrators/newton.hpp"
#include "io/obj_reader.hpp"
#include "linkage/statics_problem.hpp"
#include "beam_fixtures.hpp"
#include "toy_objectives.hpp"

using namespace xshell;
using namespace xshell::test;

namespace {

// E = k x^2 / 2 in one unknown.
class Spring : public Objective {
 public:
  Spring(double k, double x0) : k_(k), x_(Eigen::VectorXd::Constant(1, x0)), hessian_(1, 1) {
    hessian_.insert(0, 0) = k;
    hessian_.makeCompressed();
  }
  Eigen::Index size() const override { return 1; }
  Eigen::VectorXd get() const override { return x_; }
  void set(const Eigen::VectorXd& q) override { x_ = q; }
  double energy() const override { return 0.5 * k_ * x_[0] * x_[0]; }
  Eigen::VectorXd gradient() const override { return k_ * x_; }
  const Eigen::SparseMatrix<double>& hessian() override { return hessian_; }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(1); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(1); }

 private:
  double k_;
  Eigen::VectorXd x_;
  Eigen::SparseMatrix<double> hessian_;
};

struct Run {
  KineticDampingResult result;
  std::vector<KineticDampingReport> reports;

  // Largest rise of the energy from one reset (or the start) to the next
  // kinetic-energy peak reset, relative to the total drop: kinetic damping
  // only removes energy. Resets flagged as energy rises (masses found too
  // light) start a new comparison.
  double max_reset_energy_rise() const {
    double rise = 0.0, last = reports.front().energy;
    for (const KineticDampingReport& r : reports) {
      if (r.reset && !r.energy_rise) rise = std::max(rise, r.energy - last);
      if (r.reset || r.energy_rise || r.rejected) last = r.energy;
    }
    const double drop = reports.front().energy - result.energy;
    return drop > 0.0 ? rise / drop : rise;
  }
};

Run run_kinetic_damping(Objective& objective, const KineticDampingOptions& options,
                        const std::atomic<bool>* stop = nullptr) {
  Run run;
  KineticDampingCallbacks callbacks;
  callbacks.stop = stop;
  callbacks.on_iteration = [&](const KineticDampingReport& r) { run.reports.push_back(r); };
  run.result = solve_kinetic_damping(objective, options, callbacks);
  return run;
}

KineticDampingOptions tight(double tolerance = 1e-8, PeakLocation peak = PeakLocation::Barnes,
                            MassBound bound = MassBound::RowSum) {
  KineticDampingOptions options;
  options.gradient_tolerance = tolerance;
  options.peak = peak;
  options.mass_bound = bound;
  return options;
}

// The variants compared with Newton: the defaults, the other peak location,
// the other mass bound.
struct Variant {
  PeakLocation peak;
  MassBound bound;
};
const Variant kVariants[] = {{PeakLocation::Barnes, MassBound::RowSum},
                             {PeakLocation::Parabola, MassBound::RowSum},
                             {PeakLocation::Barnes, MassBound::ScaledRowSum}};

std::string label(const Variant& v) {
  return std::string(v.peak == PeakLocation::Barnes ? "Barnes" : "parabola") +
         (v.bound == MassBound::RowSum ? ", row sums" : ", scaled row sums");
}

std::string label(PeakLocation peak) {
  return peak == PeakLocation::Barnes ? "Barnes" : "parabola";
}

// |a - b| relative to `scale`, the larger of |reference| and the energy
// drop of the solve (an equilibrium energy may be 0, as Rosenbrock's).
double energy_difference(double a, double reference, double start) {
  return std::abs(a - reference) / std::max(std::abs(reference), std::abs(start - reference));
}

struct Toy {
  std::string name;
  // Solves a fresh copy with `solve`; returns the final configuration and energy.
  std::function<std::pair<Eigen::VectorXd, double>(const std::function<void(Objective&)>&)> run;
};

template <class Make>
std::pair<Eigen::VectorXd, double> solve_fresh(Make make,
                                               const std::function<void(Objective&)>& solve) {
  StencilObjective objective = make();
  solve(objective);
  return {objective.configuration(), objective.energy()};
}

std::vector<Toy> toys() {
  std::vector<Toy> list;
  list.push_back(
      {"chain", [](const auto& solve) { return solve_fresh([] { return make_chain(); }, solve); }});
  list.push_back({"rosenbrock", [](const auto& solve) {
                    return solve_fresh([] { return make_rosenbrock(8); }, solve);
                  }});
  list.push_back({"buckled column", [](const auto& solve) {
                    ColumnOptions o;
                    o.imperfection = 0.05;
                    return solve_fresh([o] { return make_column(o); }, solve);
                  }});
  list.push_back({"offset chain", [](const auto& solve) {
                    StencilObjective inner = make_chain();
                    OffsetObjective offset(inner, 0.3);
                    solve(offset);
                    return std::make_pair(offset.configuration(), offset.energy());
                  }});
  return list;
}

// --- Small linkages, as in linkage_newton_test.cpp ---

// The unit cantilever of beam_fixtures.hpp (E I = 1, clamped at vertex 0).
// The number of kinetic-damping iterations grows like sqrt(EA / EI) ~ 1 / w.
LinkageProblem cantilever(int subdivisions, const Eigen::Vector3d& tip_force, double w = 0.01) {
  return xshell::testing::cantilever_beam(subdivisions, tip_force, w);
}

LineGraph square_grid(int n) {
  LineGraph g;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g.vertices.emplace_back(0.25 * j, 0.25 * i, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * n + j;
      if (j + 1 < n) g.edges.push_back({v, v + 1});
      if (i + 1 < n) g.edges.push_back({v, v + n});
    }
  return g;
}

LinkageOptions grid_material(int subdivisions = 6) {
  LinkageOptions o;
  o.subdivisions = subdivisions;
  o.rest_shape = RestShape::Straight;
  o.material.young_modulus = 2e10;
  o.material.density = 1800;
  o.material.section = {SectionShape::Rectangle, 0.01, 0.007};
  return o;
}

LinkageProblem grid_under_gravity(int n, int subdivisions = 6) {
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0, 0, -9.81);
  for (int corner : {0, n - 1, n * (n - 1), n * n - 1})
    setup.supports.push_back({corner, {SupportDof::Position}});
  return LinkageProblem(RodLinkage(square_grid(n), grid_material(subdivisions)), setup);
}

Eigen::VectorXd stacked_positions(const LinkageProblem& problem) {
  const std::vector<Eigen::Vector3d> x = problem.vertex_positions();
  Eigen::VectorXd stacked(3 * static_cast<Eigen::Index>(x.size()));
  for (size_t i = 0; i < x.size(); ++i) stacked.segment<3>(3 * static_cast<Eigen::Index>(i)) = x[i];
  return stacked;
}

NewtonOptions newton_options(double tolerance) {
  NewtonOptions options;
  options.gradient_tolerance = tolerance;
  options.max_iterations = 500;
  options.line_search = LineSearch::Energy;
  return options;
}

}  // namespace

TEST_CASE("kinetic damping: the first peak reset lands where the leapfrog recurrence says") {
  // E = k x^2 / 2 from x0 = 1, m = safety k / 4, dt = 1. The recurrence with
  // Barnes's half start: v_{1/2} = -k x0 / (2m), v_{n+1/2} = v_{n-1/2} - k x_n / m,
  // x_{n+1} = x_n + v_{n+1/2}; its exact solution is x_n = cos(omega n),
  // cos(omega) = 1 - k / (2m) = 1 - 2 / safety.
  const double k = 3.0, safety = 50.0, m = safety * k / 4.0;
  const double omega = std::acos(1.0 - k / (2.0 * m));
  std::vector<double> x = {1.0}, v, ke;  // x_n; v[i] = v_{i+1/2}; ke[i] = KE_{i+1/2}
  for (int i = 0; i < 12; ++i) {
    const double a = -k * x.back() / m;
    v.push_back(i == 0 ? 0.5 * a : v.back() + a);
    ke.push_back(0.5 * m * v.back() * v.back());
    x.push_back(x.back() + v.back());
  }
  int closed_form = 0;
  for (size_t n = 0; n < x.size(); ++n, ++closed_form)
    CHECK(x[n] == doctest::Approx(std::cos(omega * static_cast<double>(n))).epsilon(1e-13));
  CHECK(closed_form == 13);
  // Iteration i computes x_i and KE_{i-1/2}; the peak is passed at the first
  // i with KE_{i-1/2} < KE_{i-3/2}, i.e. i - 1 > pi / (2 omega) (here 5.535).
  int detected = 0;
  for (int i = 2; i < 12 && detected == 0; ++i)
    if (ke[static_cast<size_t>(i - 1)] < ke[static_cast<size_t>(i - 2)]) detected = i;
  REQUIRE(detected == static_cast<int>(std::floor(M_PI / (2.0 * omega))) + 2);
  REQUIRE(detected == 7);
  const size_t i = static_cast<size_t>(detected);
  // Barnes: x* = x_i - 1.5 v_{i-1/2} + 0.5 M^-1 R_{i-1} = (x_{i-2} + x_{i-1}) / 2.
  const double barnes = x[i] - 1.5 * v[i - 1] + 0.5 * (-k * x[i - 1] / m);
  CHECK(barnes == doctest::Approx(0.5 * (x[i - 2] + x[i - 1])).epsilon(1e-13));
  CHECK(barnes == doctest::Approx(std::cos(omega * (detected - 1.5)) * std::cos(omega / 2.0)));
  // Parabola through KE_{i-5/2}, KE_{i-3/2}, KE_{i-1/2}, then back along v_{i-3/2}.
  const double tau = (ke[i - 3] - ke[i - 1]) / (2.0 * (ke[i - 3] - 2.0 * ke[i - 2] + ke[i - 1]));
  const double parabola = x[i - 1] - (0.5 - tau) * v[i - 2];
  // Both land near the zero crossing, the parabola much nearer.
  CHECK(std::abs(barnes) < std::sin(omega / 2.0));
  CHECK(std::abs(parabola) < 0.05 * std::abs(barnes));
  MESSAGE("spring: omega = " << omega << ", peak passed at iteration " << detected
                             << ", Barnes x* = " << barnes << ", parabola x* = " << parabola);

  int compared = 0;
  for (PeakLocation peak : {PeakLocation::Barnes, PeakLocation::Parabola}) {
    CAPTURE(label(peak));
    Spring spring(k, 1.0);
    KineticDampingOptions options = tight(1e-12, peak);
    options.mass_safety = safety;
    std::vector<double> positions;  // after each iteration
    Run run;
    KineticDampingCallbacks callbacks;
    callbacks.on_iteration = [&](const KineticDampingReport& r) {
      run.reports.push_back(r);
      positions.push_back(spring.get()[0]);
    };
    run.result = solve_kinetic_damping(spring, options, callbacks);
    REQUIRE(run.result.converged());
    REQUIRE(run.reports.size() > i);
    for (size_t j = 1; j < i; ++j) {  // the leapfrog, no reset yet
      CHECK_FALSE(run.reports[j].reset);
      CHECK(positions[j] == doctest::Approx(x[j]).epsilon(1e-14));
      CHECK(run.reports[j].kinetic_energy == doctest::Approx(ke[j - 1]).epsilon(1e-13));
      ++compared;
    }
    CHECK(run.reports[i].reset);
    CHECK(run.reports[i].kinetic_energy == 0.0);
    const double expected = peak == PeakLocation::Barnes ? barnes : parabola;
    CHECK(std::abs(positions[i] - expected) < 1e-15);
    CHECK(run.reports[i].energy == doctest::Approx(0.5 * k * expected * expected).epsilon(1e-12));
    // Every further peak shrinks the amplitude by about the same factor.
    CHECK(run.result.resets >= 2);
    CHECK(std::abs(spring.get()[0]) <= 1e-12 / k);
    CHECK(run.result.energy_rises == 0);
    CHECK(run.result.stable);
    CHECK(run.result.factorizations == 1);
    CHECK(run.max_reset_energy_rise() <= 1e-12);
    MESSAGE("spring, " << label(peak) << ": " << run.result.iterations << " iterations, "
                       << run.result.resets << " resets to |x| <= 1e-12");
    ++compared;
  }
  CHECK(compared == 2 * static_cast<int>(i));
}

TEST_CASE("kinetic damping: both Gerschgorin mass bounds hold, the scaled one ignores units") {
  // A random sparse symmetric K, indefinite, whose unknowns have scales
  // 1e-3 .. 1e3 (as positions and angles in different units).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const int n = 14;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = i; j < std::min(n, i + 4); ++j) dense(i, j) = dense(j, i) = uniform(rng);
  Eigen::VectorXd scale(n);
  for (int i = 0; i < n; ++i) scale[i] = std::pow(10.0, 3.0 * uniform(rng));
  dense = scale.asDiagonal() * dense * scale.asDiagonal();
  // The same stiffness in other units: q = C q', K' = C K C.
  Eigen::VectorXd c(n);
  for (int i = 0; i < n; ++i) c[i] = std::pow(10.0, 3.0 * uniform(rng));
  const Eigen::MatrixXd rescaled = c.asDiagonal() * dense * c.asDiagonal();
  const Eigen::SparseMatrix<double> K = dense.sparseView(), K2 = rescaled.sparseView();

  auto largest_eigenvalue = [](const Eigen::MatrixXd& A, const Eigen::VectorXd& m) {
    const Eigen::VectorXd r = m.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd S = r.asDiagonal() * A * r.asDiagonal();  // similar to M^-1 K
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().cwiseAbs().maxCoeff();
  };
  int checked = 0;
  for (const Eigen::MatrixXd* A : {static_cast<const Eigen::MatrixXd*>(&dense), &rescaled}) {
    const Eigen::SparseMatrix<double> sparse = A->sparseView();
    const double row_sum = largest_eigenvalue(*A, fictitious_mass(sparse, 0.0));
    const double scaled = largest_eigenvalue(*A, scaled_fictitious_mass(sparse));
    CHECK(row_sum <= 1.0 + 1e-12);
    CHECK(scaled <= 1.0 + 1e-12);
    CHECK(scaled > 0.1);  // a useful bound, not a huge mass
    checked += 3;
  }
  // Scaled: m' = c^2 m exactly; row sums: not at all.
  const Eigen::VectorXd ratio_scaled = scaled_fictitious_mass(K2).cwiseQuotient(
      c.cwiseAbs2().cwiseProduct(scaled_fictitious_mass(K)));
  const Eigen::VectorXd ratio_row =
      fictitious_mass(K2, 0.0).cwiseQuotient(c.cwiseAbs2().cwiseProduct(fictitious_mass(K, 0.0)));
  CHECK((ratio_scaled.array() - 1.0).abs().maxCoeff() < 1e-12);
  CHECK(ratio_row.maxCoeff() / ratio_row.minCoeff() > 10.0);
  checked += 2;
  CHECK(checked == 8);
}

TEST_CASE(
    "kinetic damping: Barnes's mass bound keeps the leapfrog stable, a light mass is caught") {
  // safety 1.05: dt^2 k / m = 3.81 < 4, stable, period about 2.4 steps.
  Spring spring(2.0, 1.0);
  KineticDampingOptions options = tight(1e-12);
  options.mass_safety = 1.05;
  const Run stable = run_kinetic_damping(spring, options);
  CHECK(stable.result.converged());
  CHECK(stable.result.energy_rises == 0);
  CHECK(stable.result.rejected_steps == 0);
  // safety 0.9: dt^2 k / m = 4.44 > 4, the leapfrog diverges from the first
  // steps; the energy rise is caught, the masses grow and the run converges.
  Spring light(2.0, 1.0);
  options.mass_safety = 0.9;
  const Run caught = run_kinetic_damping(light, options);
  INFO(caught.result.reason);
  CHECK(caught.result.converged());
  CHECK(caught.result.energy_rises >= 1);
  CHECK(caught.result.mass_safety > 1.0);
  CHECK(caught.result.mass_refreshes >= 2);
  CHECK(std::abs(light.get()[0]) <= 1e-12);
}

TEST_CASE("kinetic damping reaches Newton's equilibria on the toy objectives") {
  const NewtonOptions newton = newton_options(1e-10);
  int compared = 0;
  for (const Toy& toy : toys()) {
    const auto [reference, reference_energy] = toy.run([&](Objective& o) {
      const NewtonResult r = solve_newton(o, newton);
      REQUIRE(r.converged());
      REQUIRE(r.stable);
    });
    for (double tolerance : {1e-8, 1e-10})
      for (const Variant& variant : kVariants) {
        Run run;
        const auto [q, energy] = toy.run([&](Objective& o) {
          run = run_kinetic_damping(o, tight(tolerance, variant.peak, variant.bound));
        });
        const double distance = (q - reference).norm() / reference.norm();
        INFO(toy.name << ", " << label(variant) << ", tolerance " << tolerance << ": "
                      << run.result.reason);
        REQUIRE(run.result.converged());
        CHECK(run.result.gradient_measure <= tolerance);
        CHECK(run.result.stable);
        CHECK(distance < 1e-6);
        CHECK(energy_difference(energy, reference_energy, run.reports.front().energy) < 1e-7);
        CHECK(run.result.iterations == static_cast<long>(run.reports.size()) - 1);
        CHECK(run.result.resets >= 1);
        CHECK(run.max_reset_energy_rise() <= 1e-12);  // kinetic damping only removes energy
        CHECK(run.result.energy_rises <= 2);          // the chain stiffens (quartic) from its start
        CHECK(run.result.factorizations == 1);        // the stability check, nothing else
        ++compared;
        MESSAGE(toy.name << ", " << label(variant) << ", tolerance " << tolerance << ": "
                         << run.result.iterations << " iterations, " << run.result.resets
                         << " resets, " << run.result.energy_rises << " energy rises, "
                         << run.result.mass_refreshes << " mass refreshes, safety "
                         << run.result.mass_safety << ", |dq|/|q| = " << distance << ", "
                         << run.result.seconds << " s");
      }
  }
  CHECK(compared == 24);
}

TEST_CASE("kinetic damping rebases with transformed velocities as often as asked") {
  StencilObjective reference_inner = make_chain();
  OffsetObjective reference(reference_inner, 0.3);
  REQUIRE(solve_newton(reference, newton_options(1e-10)).converged());
  int cases = 0;
  for (long interval : {1L, 7L}) {
    CAPTURE(interval);
    StencilObjective inner = make_chain();
    OffsetObjective offset(inner, 0.3);
    KineticDampingOptions options = tight(1e-10);
    options.rebase_interval = interval;
    const Run run = run_kinetic_damping(offset, options);
    INFO(run.result.reason);
    REQUIRE(run.result.converged());
    CHECK(offset.rebases() == run.result.rebases);
    // Every reset rebases, and so does every interval-th step in between.
    CHECK(run.result.rebases >= run.result.resets);
    if (interval == 1) CHECK(run.result.rebases == run.result.iterations);
    CHECK(run.result.rebases > run.result.resets);
    CHECK((offset.configuration() - reference.configuration()).norm() <
          1e-6 * reference.configuration().norm());
    ++cases;
  }
  CHECK(cases == 2);
}

TEST_CASE("kinetic damping near the column's saddle") {
  ColumnOptions far;
  far.imperfection = 0.05;
  StencilObjective reference = make_column(far);
  REQUIRE(solve_newton(reference, newton_options(1e-10)).converged());
  const int middle = column_middle_y(far);

  SUBCASE("a tiny imperfection grows into the buckled minimum") {
    ColumnOptions near = far;
    near.imperfection = 1e-4;
    StencilObjective column = make_column(near);
    const Run run = run_kinetic_damping(column, tight(1e-10));
    INFO(run.result.reason);
    REQUIRE(run.result.converged());
    CHECK(run.result.stable);
    CHECK(column.get()[middle] > 0.05);
    CHECK((column.get() - reference.get()).norm() < 1e-6 * reference.get().norm());
    MESSAGE("column from imperfection 1e-4: " << run.result.iterations << " iterations");
  }
  SUBCASE("an exactly straight start stays on the saddle, reported unstable") {
    StencilObjective column = make_column({});
    const Run run = run_kinetic_damping(column, tight(1e-10));
    INFO(run.result.reason);
    REQUIRE(run.result.converged());
    CHECK(column.get()[middle] == 0.0);
    CHECK_FALSE(run.result.stable);
  }
}

TEST_CASE("kinetic damping: stop flag, iteration limit, invalid and non-finite states") {
  SUBCASE("converged at the start: no iteration") {
    Spring spring(1.0, 0.0);
    const Run run = run_kinetic_damping(spring, tight());
    CHECK(run.result.converged());
    CHECK(run.result.iterations == 0);
    CHECK(run.reports.size() == 1);
    CHECK(run.result.stable);
  }
  SUBCASE("stop flag") {
    StencilObjective chain = make_chain();
    std::atomic<bool> stop{false};
    Run run;
    KineticDampingCallbacks callbacks;
    callbacks.stop = &stop;
    callbacks.on_iteration = [&](const KineticDampingReport& r) {
      run.reports.push_back(r);
      if (r.iteration == 5) stop = true;
    };
    run.result = solve_kinetic_damping(chain, tight(), callbacks);
    CHECK(run.result.status == KineticDampingStatus::Interrupted);
    CHECK(run.result.iterations == 5);
    CHECK(run.reports.size() == 6);
    CHECK(std::isfinite(chain.energy()));
  }
  SUBCASE("iteration limit") {
    StencilObjective chain = make_chain();
    KineticDampingOptions options = tight();
    options.max_iterations = 7;
    const Run run = run_kinetic_damping(chain, options);
    CHECK(run.result.status == KineticDampingStatus::MaxIterations);
    CHECK(run.result.iterations == 7);
    CHECK(run.reports.size() == 8);
  }
  SUBCASE("NaN at the start") {
    SqrtWell well(Eigen::VectorXd::Constant(3, -1.0), InvalidBehaviour::NaN);
    const Run run = run_kinetic_damping(well, tight());
    CHECK(run.result.status == KineticDampingStatus::NonFinite);
    CHECK(run.result.iterations == 0);
    CHECK_FALSE(run.result.stable);
  }
  SUBCASE("a state pressed against a NaN region: NonFinite, left at the last good state") {
    SqrtWell well(Eigen::VectorXd::Constant(3, 4.0), InvalidBehaviour::NaN, 3.9);
    const Run run = run_kinetic_damping(well, tight());
    INFO(run.result.reason);
    CHECK(run.result.status == KineticDampingStatus::NonFinite);
    CHECK(run.result.rejected_steps > tight().max_rejected_steps);
    CHECK(well.invalid_encounters() > 0);
    CHECK(std::isfinite(well.energy()));
    CHECK((well.get().array() >= 3.9).all());
    CHECK(run.result.iterations == static_cast<long>(run.reports.size()) - 1);
  }
  SUBCASE("a finite energy with a NaN gradient: the step is rejected, the state kept") {
    // E = sum (x - 2 sqrt x) everywhere, but the gradient is NaN below 3.9.
    class NanGradient : public SqrtWell {
     public:
      using SqrtWell::SqrtWell;
      Eigen::VectorXd gradient() const override {
        Eigen::VectorXd g = SqrtWell::gradient();
        if ((get().array() < 3.9).any()) g.setConstant(std::nan(""));
        return g;
      }
    };
    NanGradient well(Eigen::VectorXd::Constant(3, 4.0), InvalidBehaviour::NaN);
    KineticDampingOptions options = tight();
    options.rebase_interval = 1000;  // rejections only happen between rebases
    const Run run = run_kinetic_damping(well, options);
    INFO(run.result.reason);
    CHECK(run.result.status == KineticDampingStatus::NonFinite);
    CHECK(run.result.rejected_steps > options.max_rejected_steps);
    CHECK((well.get().array() >= 3.9).all());
    CHECK(run.result.energy == well.energy());  // the energy of the state kept
    CHECK(std::isfinite(run.result.gradient_measure));
  }
  SUBCASE("a state pressed against invalid configurations: InvalidConfiguration") {
    SqrtWell well(Eigen::VectorXd::Constant(3, 4.0), InvalidBehaviour::Throw, 3.9);
    const Run run = run_kinetic_damping(well, tight());
    INFO(run.result.reason);
    CHECK(run.result.status == KineticDampingStatus::InvalidConfiguration);
    CHECK(well.invalid_encounters() > 0);
    CHECK((well.get().array() >= 3.9).all());
  }
  SUBCASE("an invalid region crossed by the motion is avoided with heavier masses") {
    // The minimum x = 1 is valid, but the first step from 30 overshoots below 0.5.
    SqrtWell well(Eigen::VectorXd::Constant(2, 30.0), InvalidBehaviour::Throw, 0.5);
    KineticDampingOptions options = tight(1e-10);
    options.mass_safety = 1.01;
    const Run run = run_kinetic_damping(well, options);
    INFO(run.result.reason);
    CHECK(run.result.converged());
    CHECK((well.get().array() - 1.0).abs().maxCoeff() < 1e-8);
    MESSAGE("sqrt well from 30: " << run.result.rejected_steps << " rejected steps, "
                                  << run.result.energy_rises << " energy rises, "
                                  << run.result.iterations << " iterations");
  }
  SUBCASE("an unexpected exception reaches the caller") {
    StencilObjective chain = make_chain();
    FaultyObjective faulty(chain, 5);
    CHECK_THROWS_AS(solve_kinetic_damping(faulty, tight()), std::runtime_error);
    CHECK(faulty.calls() >= 5);
  }
}

TEST_CASE("kinetic damping reaches Newton's equilibria of small linkages") {
  struct Case {
    std::string name;
    std::function<LinkageProblem()> make;
  };
  const std::vector<Case> cases = {
      {"cantilever 1 x 0.05 x 0.05, tip load EI/L^2 (10 edges)",
       [] { return cantilever(10, Eigen::Vector3d(0, 0, -1.0), 0.05); }},
      {"3x3 grid under gravity, 4 corner supports", [] { return grid_under_gravity(3, 4); }},
  };
  int compared = 0;
  for (const Case& c : cases) {
    LinkageProblem reference = c.make();
    const Eigen::VectorXd x_input = stacked_positions(reference);
    LinkageObjective reference_objective(reference);
    const NewtonResult newton = solve_newton(reference_objective, newton_options(1e-10));
    REQUIRE(newton.converged());
    const Eigen::VectorXd x_ref = stacked_positions(reference);
    const double e_ref = reference.energy().total();
    // Compared on displacements: positions barely move under gravity.
    const double displacement = (x_ref - x_input).norm();
    REQUIRE(displacement > 1e-4 * x_input.norm());

    for (MassBound bound : {MassBound::RowSum, MassBound::ScaledRowSum}) {
      LinkageProblem problem = c.make();
      LinkageObjective objective(problem);
      // 1e-10: two decades below the 1e-8 asked for; 1e-11 is below the
      // round-off floor of the grid's gradient measure (eps EA / F_c).
      const Run run = run_kinetic_damping(objective, tight(1e-10, PeakLocation::Barnes, bound));
      const std::string name =
          c.name + (bound == MassBound::RowSum ? ", row sums" : ", scaled row sums");
      INFO(name << ": " << run.result.reason);
      REQUIRE(run.result.converged());
      CHECK(problem.gradient_measure() <= 1e-10);
      CHECK(run.result.stable);
      const double distance = (stacked_positions(problem) - x_ref).norm() / displacement;
      CHECK(distance < 1e-6);
      CHECK(energy_difference(problem.energy().total(), e_ref, run.reports.front().energy) < 1e-7);
      CHECK(run.max_reset_energy_rise() <= 1e-12);
      ++compared;
      MESSAGE(name << ": " << problem.num_free() << " unknowns; Newton " << newton.iterations
                   << " iterations, " << newton.seconds << " s; kinetic damping "
                   << run.result.iterations << " iterations (" << run.result.resets << " resets, "
                   << run.result.energy_rises << " energy rises, " << run.result.mass_refreshes
                   << " mass refreshes), " << run.result.seconds
                   << " s; |dx|/|x - x0| = " << distance);
    }
  }
  CHECK(compared == 4);
}

TEST_CASE("kinetic damping with scaled row sums does not depend on the length unit") {
  // The 3x3 grid under gravity in SI and in mm, tonne, s (N, MPa): the same
  // problem, the same dimensionless gradient measure.
  int runs = 0;
  long scaled_iterations[2] = {0, 0}, row_sum_iterations[2] = {0, 0};
  Eigen::VectorXd positions[2];
  for (int u = 0; u < 2; ++u) {
    const double unit = u == 0 ? 1.0 : 1000.0;  // length unit per metre
    for (MassBound bound : {MassBound::RowSum, MassBound::ScaledRowSum}) {
      const int n = 3;
      LineGraph g = square_grid(n);
      for (Eigen::Vector3d& v : g.vertices) v *= unit;
      LinkageOptions o = grid_material(4);
      o.material.young_modulus /= unit * unit;
      if (u == 1) o.material.density /= 1000.0 * unit * unit * unit;  // tonne / mm^3
      o.material.section = {SectionShape::Rectangle, 0.01 * unit, 0.007 * unit};
      StaticsSetup setup;
      setup.gravity = Eigen::Vector3d(0, 0, -9.81 * unit);
      for (int corner : {0, n - 1, n * (n - 1), n * n - 1})
        setup.supports.push_back({corner, {SupportDof::Position}});
      LinkageProblem problem(RodLinkage(g, o), setup);
      LinkageObjective objective(problem);
      const Run run = run_kinetic_damping(objective, tight(1e-8, PeakLocation::Barnes, bound));
      INFO(run.result.reason);
      REQUIRE(run.result.converged());
      if (bound == MassBound::ScaledRowSum) {
        scaled_iterations[u] = run.result.iterations;
        positions[u] = stacked_positions(problem) / unit;
      } else {
        row_sum_iterations[u] = run.result.iterations;
      }
      ++runs;
    }
  }
  CHECK(runs == 4);
  CHECK(scaled_iterations[0] == scaled_iterations[1]);
  CHECK((positions[0] - positions[1]).norm() < 1e-9 * positions[0].norm());
  MESSAGE("3x3 grid, m vs mm: scaled row sums "
          << scaled_iterations[0] << " vs " << scaled_iterations[1] << " iterations, row sums "
          << row_sum_iterations[0] << " vs " << row_sum_iterations[1]);
}

// --- Benchmark against Newton and damped dynamics (validation suite) ---

namespace {

struct Timing {
  long iterations = 0;
  double seconds = 0.0;
  double cpu_seconds = 0.0;  // of this process: the machine may be shared
  double measure = 0.0;
  bool converged = false;
};

std::string scientific(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

double cpu_seconds_since(std::clock_t start) {
  return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}

// Vertices with the extreme x + y, x - y, -x + y, -x - y (the corners of a
// roughly rectangular plan), distinct.
std::vector<int> corner_vertices(const LineGraph& g) {
  std::vector<int> corners;
  for (const Eigen::Vector2d& d : {Eigen::Vector2d(1, 1), Eigen::Vector2d(1, -1),
                                   Eigen::Vector2d(-1, 1), Eigen::Vector2d(-1, -1)}) {
    int best = 0;
    for (int v = 1; v < static_cast<int>(g.vertices.size()); ++v)
      if (d.dot(g.vertices[v].head<2>()) > d.dot(g.vertices[best].head<2>())) best = v;
    if (std::find(corners.begin(), corners.end(), best) == corners.end()) corners.push_back(best);
  }
  return corners;
}

// Solves make() by Newton, damped dynamics (at most dynamics_steps; none
// if 0) and kinetic damping with the given mass bounds (each stopped after
// kd_seconds) and reports the ratios.
void benchmark(const std::string& name, const std::function<LinkageProblem()>& make,
               double tolerance, long dynamics_steps, double kd_seconds,
               const std::vector<MassBound>& bounds = {MassBound::RowSum,
                                                       MassBound::ScaledRowSum}) {
  Timing newton, dynamics;
  Eigen::VectorXd x_newton, x_input;
  double e_newton = 0.0, e_start = 0.0;
  int unknowns = 0;
  {
    LinkageProblem problem = make();
    unknowns = problem.num_free();
    LinkageObjective objective(problem);
    e_start = objective.energy();
    x_input = stacked_positions(problem);
    const std::clock_t cpu = std::clock();
    const NewtonResult r = solve_newton(objective, newton_options(tolerance));
    newton = {r.iterations, r.seconds, cpu_seconds_since(cpu), r.gradient_measure, r.converged()};
    x_newton = stacked_positions(problem);
    e_newton = problem.energy().total();
    INFO(name << ": Newton: " << r.reason);
    // Newton may stagnate just above the tolerance on the larger graphs
    // (scaled step tolerance); its state is still the reference.
    CHECK(r.gradient_measure <= 10.0 * tolerance);
  }
  if (dynamics_steps > 0) {
    LinkageProblem problem = make();
    LinkageObjective objective(problem);
    DynamicsOptions options;
    options.gradient_tolerance = tolerance;
    options.max_steps = dynamics_steps;
    const std::clock_t cpu = std::clock();
    const DynamicsResult r = solve_dynamics(objective, options);
    dynamics = {r.steps, r.seconds, cpu_seconds_since(cpu), r.gradient_measure, r.converged()};
    // Reported, not asserted: damped dynamics has tests of its own.
    WARN_MESSAGE((r.converged() || r.status == DynamicsStatus::MaxSteps),
                 name << ": dynamics: " << r.reason);
  }
  auto times = [](const Timing& t) {
    return scientific(t.seconds) + " s (cpu " + scientific(t.cpu_seconds) + " s)";
  };
  std::ostringstream line;
  line << name << " (" << unknowns << " unknowns, tolerance " << tolerance << "): Newton "
       << newton.iterations << " it " << times(newton)
       << (newton.converged ? "" : " (stopped at measure " + scientific(newton.measure) + ")")
       << "; dynamics ";
  if (dynamics_steps > 0)
    line << dynamics.iterations << " steps " << times(dynamics)
         << (dynamics.converged ? ""
                                : " (stopped at measure " + scientific(dynamics.measure) + ")");
  else
    line << "not run";
  for (MassBound bound : bounds) {
    LinkageProblem problem = make();
    LinkageObjective objective(problem);
    std::atomic<bool> stop{false};
    const auto start = std::chrono::steady_clock::now();
    KineticDampingCallbacks callbacks;
    callbacks.stop = &stop;
    callbacks.on_iteration = [&](const KineticDampingReport& r) {
      if (r.iteration % 100 == 0 &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
              kd_seconds)
        stop = true;
    };
    const std::clock_t cpu = std::clock();
    const KineticDampingResult r =
        solve_kinetic_damping(objective, tight(tolerance, PeakLocation::Barnes, bound), callbacks);
    const Timing kd = {r.iterations, r.seconds, cpu_seconds_since(cpu), r.gradient_measure,
                       r.converged()};
    INFO(name << ": kinetic damping: " << r.reason);
    CHECK((r.converged() || r.status == KineticDampingStatus::Interrupted));
    if (r.converged()) {
      CHECK((stacked_positions(problem) - x_newton).norm() < 1e-6 * (x_newton - x_input).norm());
      CHECK(energy_difference(problem.energy().total(), e_newton, e_start) < 1e-7);
    }
    line << "; kinetic damping (" << (bound == MassBound::RowSum ? "row sums" : "scaled row sums")
         << ") " << kd.iterations << " it " << times(kd)
         << (kd.converged ? "" : " (stopped at measure " + scientific(kd.measure) + ")") << " ["
         << r.resets << " resets, " << r.energy_rises << " rises, " << r.mass_refreshes
         << " mass refreshes, " << r.rebases << " rebases, safety " << r.mass_safety
         << "]: KD/Newton iterations "
         << static_cast<double>(kd.iterations) / std::max(newton.iterations, 1L) << ", cpu time "
         << kd.cpu_seconds / newton.cpu_seconds;
    if (dynamics_steps > 0)
      line << "; KD/dynamics iterations "
           << static_cast<double>(kd.iterations) / std::max(dynamics.iterations, 1L)
           << ", cpu time " << kd.cpu_seconds / dynamics.cpu_seconds;
  }
  MESSAGE(line.str());
}

}  // namespace

// Each case well under CTest's 600 s limit on an unloaded machine.
TEST_CASE("kinetic damping against Newton and damped dynamics: cantilevers" *
          doctest::test_suite("validation")) {
  benchmark(
      "cantilever 10 edges, w = 0.01", [] { return cantilever(10, Eigen::Vector3d(0, 0, -1.0)); },
      1e-8, 20000, 120.0);
  benchmark(
      "cantilever 20 edges, w = 0.01", [] { return cantilever(20, Eigen::Vector3d(0, 0, -1.0)); },
      1e-8, 20000, 120.0);
}

TEST_CASE("kinetic damping against Newton and damped dynamics: 4x4 grid" *
          doctest::test_suite("validation")) {
  benchmark(
      "4x4 grid under gravity, 6 edges per segment", [] { return grid_under_gravity(4, 6); }, 1e-8,
      20000, 120.0);
}

namespace {

LineGraph shared_graph(const std::string& file) {
  const std::filesystem::path path = std::filesystem::path(XSHELL_SHARED_DATA_DIR) / file;
  return std::filesystem::exists(path) ? read_obj(path.string()) : LineGraph{};
}

std::function<LinkageProblem()> under_gravity(const LineGraph& graph) {
  return [&graph] {
    StaticsSetup setup;
    setup.gravity = Eigen::Vector3d(0, 0, -9.81);
    for (int v : corner_vertices(graph)) setup.supports.push_back({v, {SupportDof::Position}});
    LinkageOptions o = grid_material(4);
    o.rest_shape = RestShape::Input;
    return LinkageProblem(RodLinkage(graph, o), setup);
  };
}

}  // namespace

// Kinetic damping with row sums needs about 49000 iterations here (45 s of
// one core), with scaled row sums 28000.
TEST_CASE("kinetic damping against Newton and damped dynamics: uniform_linkage" *
          doctest::test_suite("validation")) {
  const LineGraph graph = shared_graph("uniform_linkage.obj");
  if (graph.vertices.empty()) {
    MESSAGE("skipped: " << XSHELL_SHARED_DATA_DIR << " is absent");
    return;
  }
  benchmark("uniform_linkage.obj: rest shape input, gravity, 4 corner supports, 4 edges/segment",
            under_gravity(graph), 1e-8, 2000, 240.0);
}

TEST_CASE("kinetic damping against Newton and damped dynamics: sphere_open" *
          doctest::test_suite("validation")) {
  const LineGraph graph = shared_graph("sphere_open.obj");
  if (graph.vertices.empty()) {
    MESSAGE("skipped: " << XSHELL_SHARED_DATA_DIR << " is absent");
    return;
  }
  benchmark("sphere_open.obj: rest shape input, gravity, 4 corner supports, 4 edges/segment",
            under_gravity(graph), 1e-8, 2000, 150.0);
}

// Kinetic damping needs about 85000 iterations here (110 s of one core):
// one test case per mass bound.
TEST_CASE("kinetic damping against Newton and damped dynamics: sphere_open from straight" *
          doctest::test_suite("validation")) {
  const LineGraph graph = shared_graph("sphere_open.obj");
  if (graph.vertices.empty()) {
    MESSAGE("skipped: " << XSHELL_SHARED_DATA_DIR << " is absent");
    return;
  }
  benchmark(
      "sphere_open.obj: rest shape straight, default pin, 4 edges/segment",
      [&graph] { return LinkageProblem(RodLinkage(graph, grid_material(4)), StaticsSetup{}); },
      1e-8, 1000, 400.0, {MassBound::RowSum});
}

TEST_CASE("kinetic damping against Newton: sphere_open from straight with scaled row sums" *
          doctest::test_suite("validation")) {
  const LineGraph graph = shared_graph("sphere_open.obj");
  if (graph.vertices.empty()) {
    MESSAGE("skipped: " << XSHELL_SHARED_DATA_DIR << " is absent");
    return;
  }
  benchmark(
      "sphere_open.obj: rest shape straight, default pin, 4 edges/segment",
      [&graph] { return LinkageProblem(RodLinkage(graph, grid_material(4)), StaticsSetup{}); },
      1e-8, 0, 500.0, {MassBound::ScaledRowSum});
}
