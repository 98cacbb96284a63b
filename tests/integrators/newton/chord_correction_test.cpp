// Chord corrections (chord_correction.hpp): steps with a factorization
// made elsewhere, taken while they promise to converge, each kept only when
// it lowers the measure without raising the energy; and in the Newton
// solver, the same equilibrium with fewer factorizations.

#include "integrators/newton/chord_correction.hpp"

#include <doctest/doctest.h>

#include <cmath>

#include "integrators/newton/newton.hpp"
#include "integrators/toy_objectives.hpp"

namespace xshell {
namespace {

// E = k q^2 / 2 - f q (minimum at f / k), the chord's step -g / kc made
// with a stiffness kc instead of k: each correction multiplies the gradient
// by 1 - k / kc.
struct ScalarChord {
  const double k = 4.0, f = 2.0;
  test::Quadratic parabola{Eigen::MatrixXd::Constant(1, 1, k), Eigen::VectorXd::Constant(1, f)};
  ObjectiveEvaluator evaluator{parabola};
  ChordCorrection chord(double kc, double tolerance, int max_corrections) const {
    ChordCorrection c;
    c.step = [kc](const Eigen::VectorXd&, const Eigen::VectorXd& g) {
      return Eigen::VectorXd(-g / kc);
    };
    c.measure = [](const Eigen::VectorXd& g) { return g.lpNorm<Eigen::Infinity>(); };
    c.tolerance = tolerance;
    c.max_corrections = max_corrections;
    return c;
  }
  // Places q where the gradient is g and returns its energy.
  double start_at_gradient(double g) {
    parabola.set(Eigen::VectorXd::Constant(1, (g + f) / k));
    evaluator.sync();
    return parabola.energy();
  }
};

TEST_CASE(
    "Chord corrections contract at their chord's rate until the measure is within tolerance") {
  ScalarChord s;
  const double kc = 1.1 * s.k;  // rate 1 - 1/1.1 = 1/11
  const double m0 = 1e-2, m1 = 1e-4, tolerance = 1e-7;
  const double e1 = s.start_at_gradient(m1);
  const ChordOutcome out = correct_by_chords(s.evaluator, s.chord(kc, tolerance, 10), m0, e1, m1);
  // 1e-4 -> 9.1e-6 -> 8.3e-7 -> 7.5e-8: three corrections, the last one
  // below the tolerance; each was promising (m^2 / m_before <= 100 tol).
  CHECK(out.corrections == 3);
  CHECK(out.measure == doctest::Approx(m1 / (11.0 * 11.0 * 11.0)).epsilon(1e-9));
  CHECK(out.measure <= tolerance);
  CHECK(std::abs(s.parabola.gradient()[0]) == doctest::Approx(out.measure).epsilon(1e-9));
  CHECK(out.energy == doctest::Approx(s.parabola.energy()).epsilon(1e-15));
  CHECK(out.energy < e1);
}

TEST_CASE("No chord correction where the Newton step's contraction promises none") {
  ScalarChord s;
  // m1^2 / m0 = 1e-4 / 1e-1 = 1e-3, above 100 tol = 1e-5.
  const double e1 = s.start_at_gradient(1e-2);
  const Eigen::VectorXd q1 = s.parabola.get();
  const ChordOutcome out = correct_by_chords(s.evaluator, s.chord(s.k, 1e-7, 3), 1e-1, e1, 1e-2);
  CHECK(out.corrections == 0);
  CHECK(s.parabola.get() == q1);
  CHECK(out.measure == 1e-2);
  CHECK(chord_promising(1.0, 1e-4, 1e-6));
  CHECK_FALSE(chord_promising(1.0, 1e-1, 1e-6));
  CHECK_FALSE(chord_promising(1.0, 1e-7, 1e-6));  // converged already
}

TEST_CASE("A chord correction that raises the measure is undone, and the corrections stop") {
  ScalarChord s;
  // kc = k / 3: the step overshoots to -2 times the gradient.
  const double e1 = s.start_at_gradient(1e-4);
  const Eigen::VectorXd q1 = s.parabola.get();
  const ChordOutcome out =
      correct_by_chords(s.evaluator, s.chord(s.k / 3.0, 1e-7, 3), 1e-2, e1, 1e-4);
  CHECK(out.corrections == 0);
  CHECK(s.parabola.get() == q1);  // back where it started
  CHECK(out.energy == e1);
  CHECK(out.measure == 1e-4);
}

TEST_CASE("Newton with chord corrections: the chain's equilibrium with fewer factorizations") {
  NewtonOptions options;
  options.gradient_tolerance = 1e-10;
  options.max_chord_corrections = 0;
  test::StencilObjective plain = test::make_chain();
  const NewtonResult newton = solve_newton(plain, options);
  REQUIRE(newton.converged());
  CHECK(newton.chord_corrections == 0);

  options.max_chord_corrections = 3;
  test::StencilObjective chain = test::make_chain();
  long reported = 0;
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&](const NewtonReport& r) { reported += r.chord_corrections; };
  const NewtonResult chord = solve_newton(chain, options, callbacks);
  REQUIRE(chord.converged());
  CHECK(chord.stable);
  CHECK(chord.gradient_measure <= 1e-10);
  CHECK(chord.chord_corrections >= 1);
  CHECK(reported == chord.chord_corrections);
  CHECK(chord.factorizations < newton.factorizations);
  CHECK(chord.iterations < newton.iterations);
  CHECK((chain.get() - plain.get()).norm() < 1e-8);
  MESSAGE("chain: Newton " << newton.iterations << " iterations, " << newton.factorizations
                           << " factorizations; with chords " << chord.iterations << ", "
                           << chord.factorizations << " and " << chord.chord_corrections
                           << " corrections");
}

}  // namespace
}  // namespace xshell
