// The progress watch of the explicit and time-integrating solvers on made-up
// sequences of reports: converging ones never stop it, a flat one is
// stagnation, a motion that only speeds up downhill is divergence.
#include "integrators/common/progress_watch.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace xshell::test {

namespace {

struct Verdict {
  Progress progress = Progress::Continuing;
  long at = 0;  // the report that ended it (0: none did)
  std::string reason;
};

// Feeds `count` reports (energy, gradient measure, kinetic energy) of step k
// = 1, 2, ... to a watch of window 100, started at E = 1, g = 1.
template <class Report>
Verdict watch(long count, Report report) {
  ProgressWatch w(1.0, 1.0, {100, 1e-12}, "steps");
  for (long k = 1; k <= count; ++k) {
    double e = 0.0, g = 0.0, kinetic = 0.0;
    report(k, e, g, kinetic);
    const Progress p = w.observe(e, g, kinetic);
    if (p != Progress::Continuing) return {p, k, w.reason()};
  }
  return {};
}

}  // namespace

TEST_CASE("progress watch: converging runs go on, however slowly") {
  // g halves every 90 steps, kinetic energy rising throughout (the start of
  // a motion): still converging.
  const Verdict fast = watch(1000, [](long k, double& e, double& g, double& kinetic) {
    g = std::pow(0.5, k / 90.0);
    e = -1.0 + g;
    kinetic = 1.0 - g;
  });
  CHECK(fast.progress == Progress::Continuing);
  // g flat while E falls by 1e-9 per step (10^-7 per window, relative):
  // slow, but progress that floating point shows.
  const Verdict slow = watch(1000, [](long k, double& e, double& g, double& kinetic) {
    g = 0.9;
    e = 1.0 - 1e-9 * k;
    kinetic = (k % 7) * 1e-12;  // peaks: no steady acceleration
  });
  CHECK(slow.progress == Progress::Continuing);
}

TEST_CASE("progress watch: no progress beyond round-off is stagnation, at a window's end") {
  // g stays near its floor, E wanders by round-off (1e-15 relative).
  const Verdict v = watch(1000, [](long k, double& e, double& g, double& kinetic) {
    g = k < 150 ? std::pow(0.5, k / 10.0) : 3e-5 * (1.0 + 0.3 * std::sin(k));
    e = -2.0 + 1e-15 * std::sin(3.0 * k);
    kinetic = 1e-20 * (k % 3);
  });
  CHECK(v.progress == Progress::Stagnating);
  CHECK(v.at == 300);  // 101-200 still halved g; 201-300 did not
  CHECK(v.reason.rfind("stagnation: over the last 100 steps the gradient measure did not halve",
                       0) == 0);
}

TEST_CASE("progress watch: a motion that only speeds up downhill is divergence") {
  // A load that nothing holds: g constant, E falling ever faster, kinetic
  // energy rising at every step.
  const Verdict v = watch(1000, [](long k, double& e, double& g, double& kinetic) {
    g = 5.0;
    kinetic = 0.5 * double(k) * double(k);
    e = 1.0 - kinetic;
  });
  CHECK(v.progress == Progress::Diverging);
  CHECK(v.at == 100);
  CHECK(v.reason.rfind("diverging: over the last 100 steps the kinetic energy rose throughout",
                       0) == 0);
  // The same with one dip of the kinetic energy in each window (a kinetic
  // damping reset): not divergence, and E falls: not stagnation either.
  const Verdict reset = watch(1000, [](long k, double& e, double& g, double& kinetic) {
    g = 5.0;
    kinetic = (k % 50 == 0) ? 0.0 : 0.5 * double(k % 50) * double(k % 50);
    e = 1.0 - 10.0 * k;
  });
  CHECK(reset.progress == Progress::Continuing);
}

TEST_CASE("progress watch: round-off that happens to double is no divergence") {
  // E wanders at round-off, falling by 1e-17, then 4e-17, ... per window
  // (each fall twice the one before): stagnation, not divergence.
  const Verdict v = watch(1000, [](long k, double& e, double& g, double& kinetic) {
    g = 1.0;
    e = 1.0 - 1e-17 * std::pow(4.0, k / 100);
    kinetic = 0.0;
  });
  CHECK(v.progress == Progress::Stagnating);
  CHECK(v.at == 100);
}

TEST_CASE("progress watch: a slow mode rising for longer than a window is no divergence") {
  // A kinetic-damping run on a cantilever: no kinetic-energy peak in 2000
  // iterations, the energy falling by 0.1% and g not halved (before, it was
  // called diverging).
  const Verdict v = watch(1000, [](long k, double& e, double& g, double& kinetic) {
    g = 0.05;
    kinetic = 1e-6 * double(k);
    e = -0.158 - 1e-6 * double(k);
  });
  CHECK(v.progress == Progress::Continuing);
}

}  // namespace xshell::test
