// The increments of a deployment's path parameter s, from 0 (the start) to
// 1 (the target): which value the next attempt solves at, and how the
// increment changes after a success or a failure.
//
// Fixed (largest = 0): `steps` equal increments; a failed attempt halves
// the increment, a success doubles it back up to the nominal 1 / steps,
// and the accepted values always land on the grid s = k / steps (a halved
// increment is never carried past a grid point).
// Adaptive (largest > 0): the first increment is 1 / steps; a success that
// took at most kEasyIterations solver iterations without jumping to another
// branch (a saddle left, the twin's branch taken) doubles the increment up
// to `largest`; one that took more than kHardIterations brings a grown
// increment back to 1 / steps (past a fold or a pop-out a grown increment
// costs more iterations than the steps it saves); a failure halves it, and
// a halved one doubles back up to 1 / steps after any success. The steps
// land wherever the increments take them, and the last is shortened to end
// at 1 exactly.
#pragma once

namespace xshell {

class StepControl {
 public:
  // An accepted step this easy lets an adaptive increment grow.
  static constexpr long kEasyIterations = 2;
  // An accepted step this hard ends an adaptive increment's growth.
  static constexpr long kHardIterations = 5;

  // steps >= 1; largest: the largest increment of s (0: fixed increments).
  StepControl(int steps, double largest);

  bool done() const;
  // The value of s that the next attempt solves at.
  double next() const;
  // The attempt at next() was accepted after `iterations` solver
  // iterations; `jumped`: it left the path it started on.
  void accepted(long iterations, bool jumped);
  // The attempt at next() failed: the increment is halved.
  void failed();

 private:
  bool adaptive() const { return largest_ > 0.0; }
  // Fixed increments: the grid point after grid_ (1 exactly at the end).
  double next_grid() const;
  int steps_;
  double nominal_, largest_;
  double s_ = 0.0, increment_;
  int grid_ = 0;  // fixed increments: s lies on or past grid point grid_ / steps
};

}  // namespace xshell
