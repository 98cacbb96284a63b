// What the kinetic-damping tests share: a run with its reports, the
// options they tighten, the Newton reference's options, and energy
// comparisons.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "integrators/kinetic_damping/kinetic_damping.hpp"
#include "integrators/newton/newton.hpp"

namespace xshell::test {

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

inline Run run_kinetic_damping(Objective& objective, const KineticDampingOptions& options,
                               const std::atomic<bool>* stop = nullptr) {
  Run run;
  KineticDampingCallbacks callbacks;
  callbacks.stop = stop;
  callbacks.on_iteration = [&](const KineticDampingReport& r) { run.reports.push_back(r); };
  run.result = solve_kinetic_damping(objective, options, callbacks);
  return run;
}

inline KineticDampingOptions tight(double tolerance = 1e-8,
                                   PeakLocation peak = PeakLocation::Barnes,
                                   MassBound bound = MassBound::RowSum) {
  KineticDampingOptions options;
  options.gradient_tolerance = tolerance;
  options.peak = peak;
  options.mass_bound = bound;
  return options;
}

// |a - b| relative to `scale`, the larger of |reference| and the energy
// drop of the solve (an equilibrium energy may be 0, as Rosenbrock's).
inline double energy_difference(double a, double reference, double start) {
  return std::abs(a - reference) / std::max(std::abs(reference), std::abs(start - reference));
}

inline NewtonOptions newton_options(double tolerance) {
  NewtonOptions options;
  options.gradient_tolerance = tolerance;
  options.max_iterations = 500;
  options.line_search = LineSearch::Energy;
  return options;
}

}  // namespace xshell::test
