// Kinetic damping (explicit dynamic relaxation) on toy objectives: where
// the first peak reset lands, the mass bounds, Newton's equilibria, rebases,
// the column's saddle, and the stop flag, limits and failures.
#include "integrators/kinetic_damping/kinetic_damping.hpp"

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

#include "integrators/beam_fixtures.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/dynamics/mass_and_damping.hpp"
#include "integrators/kinetic_damping/kinetic_damping_support.hpp"
#include "integrators/newton/newton.hpp"
#include "integrators/toy_objectives.hpp"
#include "io/obj_reader.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell::test {

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
    CHECK(run.result.status == SolveStatus::Interrupted);
    CHECK(run.result.iterations == 5);
    CHECK(run.reports.size() == 6);
    CHECK(std::isfinite(chain.energy()));
  }
  SUBCASE("iteration limit") {
    StencilObjective chain = make_chain();
    KineticDampingOptions options = tight();
    options.max_iterations = 7;
    const Run run = run_kinetic_damping(chain, options);
    CHECK(run.result.status == SolveStatus::IterationLimit);
    CHECK(run.result.iterations == 7);
    CHECK(run.reports.size() == 8);
  }
  SUBCASE("NaN at the start") {
    SqrtWell well(Eigen::VectorXd::Constant(3, -1.0), InvalidBehaviour::NaN);
    const Run run = run_kinetic_damping(well, tight());
    CHECK(run.result.status == SolveStatus::NonFinite);
    CHECK(run.result.iterations == 0);
    CHECK_FALSE(run.result.stable);
  }
  SUBCASE("a state pressed against a NaN region: NonFinite, left at the last good state") {
    SqrtWell well(Eigen::VectorXd::Constant(3, 4.0), InvalidBehaviour::NaN, 3.9);
    const Run run = run_kinetic_damping(well, tight());
    INFO(run.result.reason);
    CHECK(run.result.status == SolveStatus::NonFinite);
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
    CHECK(run.result.status == SolveStatus::NonFinite);
    CHECK(run.result.rejected_steps > options.max_rejected_steps);
    CHECK((well.get().array() >= 3.9).all());
    CHECK(run.result.energy == well.energy());  // the energy of the state kept
    CHECK(std::isfinite(run.result.gradient_measure));
  }
  SUBCASE("a state pressed against invalid configurations: InvalidConfiguration") {
    SqrtWell well(Eigen::VectorXd::Constant(3, 4.0), InvalidBehaviour::Throw, 3.9);
    const Run run = run_kinetic_damping(well, tight());
    INFO(run.result.reason);
    CHECK(run.result.status == SolveStatus::InvalidConfiguration);
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

TEST_CASE("kinetic damping stops on stagnation below the round-off floor") {
  SUBCASE("a tolerance of 1e-30: stagnation, long before the iteration limit") {
    // Before: every iteration up to the limit (16,726 in 120 s on the sample).
    StencilObjective chain = make_chain();
    KineticDampingOptions options = tight(1e-30);  // the default watch
    options.max_iterations = 300000;
    const Run run = run_kinetic_damping(chain, options);
    INFO(run.result.reason);
    CHECK(run.result.status == SolveStatus::IntegratorFailed);
    CHECK(run.result.reason.rfind("stagnation: over the last ", 0) == 0);
    CHECK(run.result.iterations < 100000);
    // At the floor: what a reachable tolerance converges to.
    StencilObjective again = make_chain();
    const Run converged = run_kinetic_damping(again, tight(1e-8));
    REQUIRE(converged.result.converged());
    CHECK(converged.result.iterations < run.result.iterations);
    CHECK(energy_difference(run.result.energy, converged.result.energy,
                            converged.reports.front().energy) < 1e-8);
  }
  SUBCASE("the windows of progress_watch.hpp, when asked for, still stop it") {
    StencilObjective chain = make_chain();
    KineticDampingOptions options = tight(1e-30);
    options.watch.enabled = false;
    options.progress = {2000, 1e-12, 10, false};
    const Run run = run_kinetic_damping(chain, options);
    INFO(run.result.reason);
    CHECK(run.result.status == SolveStatus::IntegratorFailed);
    CHECK(run.result.reason.rfind("stagnation: over the last 20000 iterations", 0) == 0);
    CHECK(run.result.iterations % 2000 == 0);  // at a window's end
  }
}

namespace {

// Two unknowns joined by a stiff spring k, both pushed by a force f, on a
// weak hill of curvature -a: E = k (x - y)^2 / 2 - f (x + y) - a (x^2 + y^2) / 2.
// No equilibrium downhill: the pair speeds up and its gradient f + a x grows
// without bound (slowly: the masses follow the spring, a / k = 1e-5).
class Runaway : public Objective {
 public:
  Runaway() : q_(Eigen::VectorXd::Zero(2)), hessian_(2, 2) {
    hessian_.insert(0, 0) = k_ - a_;
    hessian_.insert(1, 1) = k_ - a_;
    hessian_.insert(0, 1) = -k_;
    hessian_.insert(1, 0) = -k_;
    hessian_.makeCompressed();
  }
  Eigen::Index size() const override { return 2; }
  Eigen::VectorXd get() const override { return q_; }
  void set(const Eigen::VectorXd& q) override { q_ = q; }
  double energy() const override {
    return 0.5 * k_ * (q_[0] - q_[1]) * (q_[0] - q_[1]) - f_ * q_.sum() -
           0.5 * a_ * q_.squaredNorm();
  }
  Eigen::VectorXd gradient() const override {
    Eigen::VectorXd g(2);
    g[0] = k_ * (q_[0] - q_[1]) - f_ - a_ * q_[0];
    g[1] = k_ * (q_[1] - q_[0]) - f_ - a_ * q_[1];
    return g;
  }
  const Eigen::SparseMatrix<double>& hessian() override { return hessian_; }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(2); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(2); }

 private:
  double k_ = 1e5, a_ = 1.0, f_ = 1.0;
  Eigen::VectorXd q_;
  Eigen::SparseMatrix<double> hessian_;
};

}  // namespace

TEST_CASE("kinetic damping stops a motion that speeds up away from any equilibrium") {
  // Before: every iteration up to the limit, the gradient at 1e300 and beyond.
  Runaway runaway;
  KineticDampingOptions options = tight(1e-8);
  options.max_iterations = 100000;
  const Run run = run_kinetic_damping(runaway, options);
  INFO(run.result.reason);
  CHECK(run.result.status == SolveStatus::Diverged);
  CHECK(run.result.reason.rfind("diverging: over the last 2000 iterations the kinetic energy rose",
                                0) == 0);
  CHECK(run.result.iterations < 20000);
  CHECK(std::isfinite(run.result.energy));
}

}  // namespace xshell::test
