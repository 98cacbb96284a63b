// Chord corrections (docs/model.md 9.9): after a full Newton step of an
// unshifted Hessian K (factorized at q0) from gradient measure m0 to m1 at
// q1, the steps
//   q_{k+1} = q_k + p(q_k, g(q_k)),   p from the same factorization of K,
// (the simplified Newton, or chord, method) cost a solve and an energy and
// gradient evaluation each, where a Newton iteration assembles and
// factorizes the Hessian again. They contract the error by about
// |K^-1 (H(q_k) - K)| = O(|q_k - q0|), which the Newton step's own
// contraction m1 / m0 estimates: the next measure is about m_k^2 / m_{k-1}.
// A correction is tried while that estimate is within kChordMargin times
// the tolerance (it should converge, or nearly), up to max_corrections;
// each must lower the measure and keep the energy within round-off of the
// point before it, else the state returns there and corrections stop.
// Regular deployment steps and the analysis' solves end in one or two
// such corrections instead of one more Newton iteration.
#pragma once

#include <Eigen/Core>
#include <functional>

#include "integrators/common/objective_evaluator.hpp"

namespace xshell {

struct ChordCorrection {
  // The step at q with gradient g, solved with the iteration's factorization.
  std::function<Eigen::VectorXd(const Eigen::VectorXd& q, const Eigen::VectorXd& g)> step;
  // The solver's convergence measure of a gradient.
  std::function<double(const Eigen::VectorXd& g)> measure;
  double tolerance = 0.0;  // the solver's gradient tolerance
  int max_corrections = 0;
};

struct ChordOutcome {
  int corrections = 0;   // accepted
  double energy = 0.0;   // at the final point
  double measure = 0.0;  // likewise
};

// Whether a correction is worth trying at measure m after one that went
// from m_before to m (docs/model.md 9.9).
bool chord_promising(double m_before, double m, double tolerance);

// From the evaluator's position q1 (energy e1, measure m1, reached from
// measure m0 by the full Newton step), the corrections above. Leaves the
// objective (synced) at the last accepted point.
ChordOutcome correct_by_chords(ObjectiveEvaluator& evaluator, const ChordCorrection& chord,
                               double m0, double e1, double m1);

}  // namespace xshell
