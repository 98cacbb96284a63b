#include "integrators/deployment/predicted_start.hpp"

#include <cmath>
#include <stdexcept>

namespace xshell {

PredictedStart lowest_energy_start(LinkageProblem& problem,
                                   const std::vector<Eigen::VectorXd>& candidates) {
  PredictedStart best;
  int current = -1;  // the candidate the problem is at
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    try {
      problem.set_free_dofs(candidates[i]);
    } catch (const std::domain_error&) {
      continue;
    }
    current = i;
    const double energy = problem.energy().total();
    const bool better = best.index < 0 || (!std::isfinite(best.energy) && std::isfinite(energy)) ||
                        energy < best.energy;
    if (better) best = {i, energy};
  }
  if (best.index >= 0 && best.index != current) problem.set_free_dofs(candidates[best.index]);
  return best;
}

}  // namespace xshell
