#include "integrators/kinetic_damping/kinetic_damping_watch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "integrators/common/solve_result.hpp"

namespace xshell {

namespace {

std::string times(double factor) {
  char text[32];
  std::snprintf(text, sizeof text, "%g times", factor);
  return text;
}

}  // namespace

KineticDampingWatch::KineticDampingWatch(double start_energy, double start_gradient_measure,
                                         KineticDampingWatchOptions options)
    : options_(options),
      start_energy_(start_energy),
      best_(start_gradient_measure),
      mark_best_(start_gradient_measure),
      mark_energy_(start_energy),
      block_best_before_(start_gradient_measure),
      block_smallest_(std::numeric_limits<double>::infinity()) {}

KineticDampingProgress KineticDampingWatch::observe(long iteration, double energy,
                                                    double gradient_measure,
                                                    double kinetic_energy) {
  if (!options_.enabled) return KineticDampingProgress::Continuing;
  if (diverging(iteration, gradient_measure, kinetic_energy))
    return KineticDampingProgress::Diverging;
  best_ = std::min(best_, gradient_measure);
  if (best_ <= 0.5 * mark_best_) {  // progress: a new mark
    mark_best_ = best_;
    mark_iteration_ = iteration;
    mark_energy_ = energy;
    largest_kinetic_ = 0.0;
    return KineticDampingProgress::Continuing;
  }
  largest_kinetic_ = std::max(largest_kinetic_, kinetic_energy);
  return stagnating(iteration, energy) ? KineticDampingProgress::Stagnating
                                       : KineticDampingProgress::Continuing;
}

bool KineticDampingWatch::stagnating(long iteration, double energy) {
  const long span = iteration - mark_iteration_;
  if (span < std::max(options_.min_window, mark_iteration_)) return false;
  const double scale = std::max(std::abs(energy), std::abs(start_energy_ - energy));
  const double fall = mark_energy_ - energy;
  if (largest_kinetic_ > options_.kinetic_round_off * scale ||
      fall > options_.energy_round_off * scale) {
    // Visible motion: a slow mode. Judge the span afresh from here.
    mark_iteration_ = iteration;
    mark_energy_ = energy;
    largest_kinetic_ = 0.0;
    return false;
  }
  reason_ = "stagnation: over the last " + std::to_string(span) +
            " iterations the gradient measure did not halve (smallest " + scientific(best_) +
            "), the kinetic energy stayed below round-off (at most " +
            scientific(largest_kinetic_) + ") and the energy did not fall beyond round-off (from " +
            scientific(mark_energy_) + " to " + scientific(energy) +
            "): round-off floor above the tolerance?";
  return true;
}

bool KineticDampingWatch::diverging(long iteration, double gradient_measure,
                                    double kinetic_energy) {
  const bool rising = kinetic_energy > last_kinetic_;
  last_kinetic_ = kinetic_energy;
  if (!rising || block_start_ == 0) {  // a peak (or the start): a new block at the next rise
    block_start_ = rising ? iteration : 0;
    block_best_before_ = best_;
    block_smallest_ = gradient_measure;
    return false;
  }
  block_smallest_ = std::min(block_smallest_, gradient_measure);
  const long span = iteration - block_start_ + 1;
  if (span < options_.window) return false;
  if (!(block_smallest_ > options_.growth_factor * block_best_before_)) {
    // Still rising, but not away from the best state: judge the next block.
    block_start_ = iteration + 1;
    block_best_before_ = std::min(best_, gradient_measure);
    block_smallest_ = std::numeric_limits<double>::infinity();
    return false;
  }
  reason_ = "diverging: over the last " + std::to_string(span) +
            " iterations the kinetic energy rose throughout (to " + scientific(kinetic_energy) +
            ") while the gradient measure stayed above " + scientific(block_smallest_) +
            ", more than " + times(options_.growth_factor) + " its smallest before (" +
            scientific(block_best_before_) +
            "): no equilibrium within reach (loads too large, or rigid motions free?)";
  return true;
}

}  // namespace xshell
