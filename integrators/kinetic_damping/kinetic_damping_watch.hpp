// Whether kinetic damping still approaches an equilibrium, from what every
// iteration reports: the energy E, the gradient measure g (dimensionless,
// as the convergence test) and the kinetic energy K.
//
// The windows of progress_watch.hpp do not fit kinetic damping: on real
// linkages it can stay 20,000 iterations without halving g near a 1e-8
// tolerance and then converge, and a slow mode from a stress-free start
// gains kinetic energy through a whole window. So:
//
// Stagnation, at the round-off floor of g: since g last halved (the
// "mark": the smallest g so far fell to half the smallest at the previous
// mark), at least max(min_window, iterations before the mark) iterations
// have passed (a window that grows with the run: a run that took N
// iterations to get somewhere gets N more to improve on it), and over
// them
//   - no kinetic energy exceeded kinetic_round_off * max(|E|, |E_0 - E|):
//     the motion is too small for E to show it (at the floor the gradient
//     is round-off noise and a peak follows every few iterations), and
//   - E did not fall by more than energy_round_off * max(|E|, |E_0 - E|).
// A run converging slowly moves a slow mode with kinetic energy that E can
// show, or has halved g within as many iterations as it has run.
//
// Divergence: over a window of `window` iterations the kinetic energy rose
// at every iteration (no peak: the motion only speeds up) while g stayed
// above growth_factor times its smallest value before the window: the run
// accelerates away from the best state it found (the sample with a force
// of 1e30). A slow mode moving towards an equilibrium also gains kinetic
// energy for a long time, but its gradient falls. Not caught: a motion
// downhill whose gradient stays bounded (a dead load on a rigid motion no
// support holds): it runs to the iteration limit.
#pragma once

#include <string>

namespace xshell {

struct KineticDampingWatchOptions {
  bool enabled = true;
  long min_window = 2000;            // iterations, at least, without halving g (stagnation)
  double kinetic_round_off = 1e-14;  // K below this times the energy scale: no visible motion
  double energy_round_off = 1e-12;   // relative fall of E below which E did not fall
  long window = 2000;                // iterations of rising K (divergence)
  double growth_factor = 10.0;       // g above this times its smallest before (divergence)
};

enum class KineticDampingProgress { Continuing, Diverging, Stagnating };

class KineticDampingWatch {
 public:
  // At the start of a solve: its energy and gradient measure.
  KineticDampingWatch(double start_energy, double start_gradient_measure,
                      KineticDampingWatchOptions options = {});

  // The state after iteration `iteration` (1, 2, ...). Returns Diverging or
  // Stagnating (and the reason, one line) when the run shows either.
  KineticDampingProgress observe(long iteration, double energy, double gradient_measure,
                                 double kinetic_energy);

  // Why the last observe() did not return Continuing.
  const std::string& reason() const { return reason_; }

 private:
  bool stagnating(long iteration, double energy);
  bool diverging(long iteration, double gradient_measure, double kinetic_energy);

  KineticDampingWatchOptions options_;
  std::string reason_;
  double start_energy_;  // E_0
  double best_;          // smallest g so far
  // Stagnation: since the last halving of g.
  double mark_best_;              // smallest g at the mark
  long mark_iteration_ = 0;       // iteration of the mark
  double mark_energy_;            // E at the mark
  double largest_kinetic_ = 0.0;  // largest K since the mark
  // Divergence: the current block of rising K.
  double last_kinetic_ = 0.0;
  long block_start_ = 0;      // first iteration of the block (0: K not rising)
  double block_best_before_;  // smallest g before the block
  double block_smallest_;     // smallest g in the block
};

}  // namespace xshell
