// Whether an explicit or time-integrating solve (kinetic damping, damped
// dynamics) still approaches an equilibrium, judged over windows of
// iterations (or time steps) from what every iteration reports: the
// energy E, the gradient measure g (dimensionless, as the convergence test)
// and the kinetic energy K.
//
// Over each window of `window` iterations, when the smallest g of the window
// is not below half the smallest g before it (no progress towards the
// tolerance), the solve is
//   - diverging when, besides, E fell by more than its whole scale so far
//     (max(|E|, |E_0 - E|) at the window's start: a slow mode can take more
//     than a window to reach its kinetic-energy peak, but falls less) and
//     either K rose at every iteration of the window or E fell at least
//     twice as far as in the window before: the motion only speeds up, downhill, away from any
//     equilibrium (a load no support can hold, or one too large for the
//     linkage), where a converging motion slows down;
//   - stagnating when, besides, E did not fall by more than
//     energy_round_off * max(|E|, |E_0 - E|) (E at the start, E_0): no
//     progress that floating point can show (a tolerance below the
//     round-off floor of g).
// A solve that converges, however slowly, halves g or lowers E in every
// window and is never stopped.
#pragma once

#include <string>

namespace xshell {

struct ProgressWatchOptions {
  long window = 2000;               // iterations (or time steps) per window, >= 1
  double energy_round_off = 1e-12;  // relative fall of E below which E did not fall
  // Stagnation only after this many windows in a row without progress (a
  // run near its tolerance may halve g slowly while E stays at round-off).
  int stagnant_windows = 1;
  // Whether to judge divergence (kinetic damping: no; a slow mode from a
  // stress-free start rises through a whole window on real linkages).
  bool divergence = true;
};

enum class Progress { Continuing, Diverging, Stagnating };

class ProgressWatch {
 public:
  // At the start of a solve: its energy and gradient measure; `unit` names
  // the iterations in reasons ("iterations", "steps").
  ProgressWatch(double start_energy, double start_gradient_measure,
                ProgressWatchOptions options = {}, std::string unit = "iterations");

  // The state after one more iteration. Returns Diverging or Stagnating
  // (and the reason, one line) at the end of a window that shows either,
  // else Continuing.
  Progress observe(double energy, double gradient_measure, double kinetic_energy);

  // Why the last observe() did not return Continuing.
  const std::string& reason() const { return reason_; }

 private:
  void start_window(double energy, double kinetic_energy);

  ProgressWatchOptions options_;
  std::string unit_;
  std::string reason_;
  double start_energy_;  // E_0
  double best_before_;   // smallest g before the window
  double best_in_window_;
  double window_energy_;  // E at the window's start
  double window_kinetic_;
  double last_kinetic_;
  bool kinetic_rising_ = true;  // K rose at every iteration of the window
  double previous_fall_ = 0.0;  // how far E fell in the window before
  long in_window_ = 0;
  int stagnant_in_a_row_ = 0;
};

}  // namespace xshell
