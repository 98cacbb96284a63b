#include "integrators/dynamics/ida_step_cap.hpp"

#include <algorithm>
#include <limits>

namespace xshell {

double DefiniteStepCap::on_failure(double cj) {
  if (!(cj > 0.0)) return cap_;
  // The failure came soon after a lift: the saddle is still there.
  if (since_lift_ >= 0) wait_ = std::min(2 * wait_, options_.max_wait);
  since_lift_ = -1;
  since_failure_ = 0;
  cap_ = std::min(cap_, options_.fraction / cj);
  return cap_;
}

bool DefiniteStepCap::on_step() {
  if (active()) {
    if (++since_failure_ < wait_) return false;
    cap_ = std::numeric_limits<double>::infinity();
    since_lift_ = 0;
    return true;
  }
  // A lift that held for as long as the wait: back to the shortest wait.
  if (since_lift_ >= 0 && ++since_lift_ >= wait_) {
    wait_ = options_.wait;
    since_lift_ = -1;
  }
  return false;
}

}  // namespace xshell
