#include "integrators/common/progress_watch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "integrators/common/solve_result.hpp"

namespace xshell {

ProgressWatch::ProgressWatch(double start_energy, double start_gradient_measure,
                             ProgressWatchOptions options, std::string unit)
    : options_(options),
      unit_(std::move(unit)),
      start_energy_(start_energy),
      best_before_(start_gradient_measure) {
  options_.window = std::max(options_.window, 1L);
  start_window(start_energy, 0.0);
}

void ProgressWatch::start_window(double energy, double kinetic_energy) {
  best_in_window_ = std::numeric_limits<double>::infinity();
  window_energy_ = energy;
  window_kinetic_ = last_kinetic_ = kinetic_energy;
  kinetic_rising_ = true;
  in_window_ = 0;
}

Progress ProgressWatch::observe(double energy, double gradient_measure, double kinetic_energy) {
  best_in_window_ = std::min(best_in_window_, gradient_measure);
  if (!(kinetic_energy > last_kinetic_)) kinetic_rising_ = false;
  last_kinetic_ = kinetic_energy;
  if (++in_window_ < options_.window) return Progress::Continuing;

  const bool halved = best_in_window_ <= 0.5 * best_before_;
  const double fall = window_energy_ - energy;
  const double scale = std::max(std::abs(energy), std::abs(start_energy_ - energy));
  const std::string window = "over the last " + std::to_string(options_.window) + " " + unit_;
  const std::string windows =
      "over the last " + std::to_string(options_.window * std::max(options_.stagnant_windows, 1)) +
      " " + unit_;
  const bool fell = fall > options_.energy_round_off * scale;  // beyond round-off
  const bool accelerating = previous_fall_ > 0.0 && fall >= 2.0 * previous_fall_;
  // A slow mode may take longer than a window to reach its kinetic-energy
  // peak: divergence also needs a fall beyond the energy's whole scale so far.
  const bool far =
      fall > std::max(std::abs(window_energy_), std::abs(start_energy_ - window_energy_));
  Progress verdict = Progress::Continuing;
  if (options_.divergence && !halved && fell && far && (kinetic_rising_ || accelerating)) {
    verdict = Progress::Diverging;
    reason_ = "diverging: " + window + " " +
              (kinetic_rising_ ? "the kinetic energy rose throughout (to " +
                                     scientific(kinetic_energy) + ") and the energy fell"
                               : std::string("the energy fell faster than before")) +
              " (from " + scientific(window_energy_) + " to " + scientific(energy) +
              ") while the gradient measure did not halve (smallest " +
              scientific(best_in_window_) +
              "): no equilibrium within reach (loads too large, or rigid motions free?)";
  } else if (!halved && !fell && ++stagnant_in_a_row_ >= options_.stagnant_windows) {
    verdict = Progress::Stagnating;
    reason_ = "stagnation: " + windows + " the gradient measure did not halve (smallest " +
              scientific(best_in_window_) +
              ") and the energy did not fall beyond round-off (from " + scientific(window_energy_) +
              " to " + scientific(energy) +
              "): round-off floor above the tolerance, or no way down?";
  }
  if (halved || fell) stagnant_in_a_row_ = 0;
  best_before_ = std::min(best_before_, best_in_window_);
  previous_fall_ = fall;
  start_window(energy, kinetic_energy);
  return verdict;
}

}  // namespace xshell
