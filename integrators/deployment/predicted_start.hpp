// The choice between a continuation step's predicted starts: every
// candidate lies on the same constraint value, so their energies compare
// directly, and the lower one is the better guess of the equilibrium
// there. The curved predictor (path_predictor.hpp) extrapolates the path
// through its last two equilibria; across a snap-through, where the last
// step jumped to another branch, that extrapolation lands far off the path
// (on the largest benchmark design the cubic's start had an energy of
// 4.8e10 against the tangent's 1.0e7, the equilibrium's being 4.8e6), and
// the tangent alone starts the step instead (docs/model.md 9.3).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "linkage/statics_problem.hpp"

namespace xshell {

struct PredictedStart {
  int index = -1;       // of the chosen candidate; -1: the problem rejected every one
  double energy = 0.0;  // its energy
};

// Moves `problem` to each candidate (free unknowns) in turn and leaves it
// at the one of lowest energy, the earliest of equal ones. Candidates that
// the problem rejects (std::domain_error: a terminal edge of non-positive
// length, non-finite joint parameters) are skipped; one of non-finite
// energy is chosen only when no other is valid. With index -1 the problem
// is left wherever its last valid state was: the caller restores it.
PredictedStart lowest_energy_start(LinkageProblem& problem,
                                   const std::vector<Eigen::VectorXd>& candidates);

}  // namespace xshell
