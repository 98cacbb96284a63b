#include "integrators/deployment/step_control.hpp"

#include <algorithm>

namespace xshell {

namespace {

// Relative distance below which a value counts as the grid point or end it
// is about to reach (no sliver of a step is left before it).
constexpr double kSnap = 1e-12;

}  // namespace

StepControl::StepControl(int steps, double largest)
    : steps_(steps),
      nominal_(1.0 / steps),
      largest_(largest > 0.0 ? std::max(largest, nominal_) : 0.0),
      increment_(nominal_) {}

bool StepControl::done() const { return adaptive() ? s_ >= 1.0 : grid_ >= steps_; }

double StepControl::next_grid() const { return grid_ + 1 == steps_ ? 1.0 : (grid_ + 1) * nominal_; }

double StepControl::next() const {
  if (adaptive()) return s_ + increment_ >= 1.0 - kSnap ? 1.0 : s_ + increment_;
  return s_ + increment_ >= next_grid() * (1.0 - kSnap) ? next_grid() : s_ + increment_;
}

void StepControl::accepted(long iterations, bool jumped) {
  const double target = next();
  if (!adaptive() && target == next_grid()) ++grid_;
  s_ = target;
  const bool easy = iterations <= kEasyIterations && !jumped;
  if (adaptive() && (iterations > kHardIterations || jumped))
    increment_ = std::min(increment_, nominal_);
  const double ceiling = adaptive() && easy ? largest_ : nominal_;
  if (increment_ < ceiling) increment_ = std::min(2.0 * increment_, ceiling);
}

void StepControl::failed() { increment_ = 0.5 * (next() - s_); }

}  // namespace xshell
