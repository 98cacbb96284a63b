#include "integrators/newton/chord_correction.hpp"

#include <cmath>
#include <stdexcept>

namespace xshell {

namespace {

// A correction is tried while m^2 / m_before (the next measure, were the
// contraction to stay as it was) is at most this multiple of the
// tolerance. The deployments' benchmark (--reps 1) with at most 3
// corrections: 100 and 1e4 gave the same iterations within 2 (manta_ray
// 59 and 57, hourglass 35 and 35); at most 8 with 1e6, 2-4 fewer
// (hourglass 31), without a clear gain in seconds.
constexpr double kChordMargin = 100.0;

// Energy changes below this multiple of |E| are round-off at a converging
// equilibrium (DescentStepOptions::endgame_energy_change is the line
// search's larger end-game threshold).
constexpr double kEnergyRoundOff = 1e-10;

}  // namespace

bool chord_promising(double m_before, double m, double tolerance) {
  return m > tolerance && m * m <= kChordMargin * tolerance * m_before;
}

ChordOutcome correct_by_chords(ObjectiveEvaluator& evaluator, const ChordCorrection& chord,
                               double m0, double e1, double m1) {
  ChordOutcome out{0, e1, m1};
  double m_before = m0;
  while (out.corrections < chord.max_corrections &&
         chord_promising(m_before, out.measure, chord.tolerance)) {
    const Eigen::VectorXd q = evaluator.position();
    bool better = false;
    double energy = 0.0, measure = 0.0;
    try {
      const Eigen::VectorXd p = chord.step(q, evaluator.gradient());
      energy = evaluator.energy_at(q + p);
      measure = chord.measure(evaluator.gradient());
      better = std::isfinite(energy) && measure < out.measure &&
               energy <= out.energy + kEnergyRoundOff * std::abs(out.energy);
    } catch (const std::domain_error&) {  // an invalid configuration
    }
    if (!better) {
      evaluator.objective().set(q);
      evaluator.sync();
      break;
    }
    m_before = out.measure;
    out = {out.corrections + 1, energy, measure};
  }
  return out;
}

}  // namespace xshell
