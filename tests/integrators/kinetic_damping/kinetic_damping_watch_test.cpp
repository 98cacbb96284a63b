// The stagnation and divergence tests of kinetic damping on made-up
// sequences of reports: slow convergence and slow modes go on, a flat run at
// round-off is stagnation (in a window that grows with the run), a motion
// that speeds up away from its best state is divergence.
#include "integrators/kinetic_damping/kinetic_damping_watch.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

namespace xshell::test {

namespace {

struct Verdict {
  KineticDampingProgress progress = KineticDampingProgress::Continuing;
  long at = 0;  // the iteration that ended it (0: none did)
  std::string reason;
};

// Feeds `count` reports (energy, gradient measure, kinetic energy) of
// iterations k = 1, 2, ... to a watch with the default options, started at
// E = -1, g = 1.
template <class Report>
Verdict watch(long count, Report report) {
  KineticDampingWatch w(-1.0, 1.0);
  for (long k = 1; k <= count; ++k) {
    double e = 0.0, g = 0.0, kinetic = 0.0;
    report(k, e, g, kinetic);
    const KineticDampingProgress p = w.observe(k, e, g, kinetic);
    if (p != KineticDampingProgress::Continuing) return {p, k, w.reason()};
  }
  return {};
}

// A peak every `period` iterations: the kinetic energy rises from 0 to
// `peak` and drops back.
double sawtooth(long k, long period, double peak) {
  return peak * static_cast<double>(k % period) / static_cast<double>(period);
}

}  // namespace

TEST_CASE("kinetic damping watch: converging runs go on, however slowly") {
  // g halves every 1900 iterations, the motion below round-off: converging.
  const Verdict slow = watch(60000, [](long k, double& e, double& g, double& kinetic) {
    e = -2.0;
    g = std::pow(0.5, static_cast<double>(k) / 1900.0);
    kinetic = sawtooth(k, 4, 1e-20);
  });
  CHECK(slow.progress == KineticDampingProgress::Continuing);
  // 6,000 iterations to reach 1e-3, then 20,000 without halving g while a
  // slow mode moves (kinetic energy 1e-10 of the energy), then converging:
  // never stopped (the case that kept progress_watch.hpp off).
  const Verdict plateau = watch(40000, [](long k, double& e, double& g, double& kinetic) {
    e = -2.0;
    g = k < 6000    ? std::pow(1e-3, k / 6000.0)
        : k < 26000 ? 1e-3
                    : 1e-3 * std::exp(-(k - 26000) / 1000.0);
    kinetic = sawtooth(k, 3000, 2e-10);
  });
  CHECK(plateau.progress == KineticDampingProgress::Continuing);
  // A slow mode from a stress-free start: kinetic energy rising for 5,000
  // iterations while g falls.
  const Verdict mode = watch(5000, [](long k, double& e, double& g, double& kinetic) {
    const double t = static_cast<double>(k) / 5000.0 * 1.5;
    e = -1.0 - std::sin(t);
    g = std::cos(t);
    kinetic = std::sin(t) * std::sin(t);
  });
  CHECK(mode.progress == KineticDampingProgress::Continuing);
}

TEST_CASE("kinetic damping watch: flat at round-off is stagnation, in a window that grows") {
  // g halves until iteration 9,000 (the mark), then stays at 1e-9 with the
  // motion below round-off: stopped 9,000 iterations after the mark.
  const Verdict flat = watch(100000, [](long k, double& e, double& g, double& kinetic) {
    e = -2.0;
    g = std::max(std::pow(0.5, static_cast<double>(k) / 300.0), 1e-9);
    kinetic = sawtooth(k, 3, 1e-20);
  });
  REQUIRE(flat.progress == KineticDampingProgress::Stagnating);
  const long mark = static_cast<long>(std::ceil(300.0 * std::log2(1e9)));  // g reaches 1e-9
  CHECK(flat.at >= 2 * (mark - 300));
  CHECK(flat.at <= 2 * mark + 1);
  CHECK(flat.reason.rfind("stagnation: over the last ", 0) == 0);
  INFO(flat.reason);
  CHECK(flat.reason.find("did not halve (smallest 1.000e-09)") != std::string::npos);
  // Early in a run the window is min_window (2,000).
  const Verdict early = watch(100000, [](long, double& e, double& g, double& kinetic) {
    e = -2.0;
    g = 1e-6;
    kinetic = 0.0;
  });
  REQUIRE(early.progress == KineticDampingProgress::Stagnating);
  CHECK(early.at == 2001);  // the mark at iteration 1 (g fell from 1 to 1e-6)
  // The same flat run, but with the energy still falling beyond round-off:
  // not stagnation.
  const Verdict falling = watch(100000, [](long k, double& e, double& g, double& kinetic) {
    e = -2.0 - 1e-9 * static_cast<double>(k);
    g = 1e-6;
    kinetic = 0.0;
  });
  CHECK(falling.progress == KineticDampingProgress::Continuing);
}

TEST_CASE("kinetic damping watch: speeding up away from the best state is divergence") {
  // After a few iterations at g = 1 the motion only speeds up and g grows
  // a hundredfold: diverging at the end of the first window that lies
  // wholly above 10 times the best (the second: the first holds g = 1).
  const Verdict away = watch(100000, [](long k, double& e, double& g, double& kinetic) {
    e = -1.0 - 1e3 * static_cast<double>(k);
    g = k < 10 ? 1.0 : 100.0 + static_cast<double>(k);
    kinetic = 1e3 * static_cast<double>(k);
  });
  REQUIRE(away.progress == KineticDampingProgress::Diverging);
  CHECK(away.at == 4000);
  CHECK(away.reason.rfind("diverging: over the last 2000 iterations the kinetic energy rose", 0) ==
        0);
  // The same with a peak every 1,500 iterations: no divergence.
  const Verdict peaks = watch(100000, [](long k, double& e, double& g, double& kinetic) {
    e = -1.0 - 1e3 * static_cast<double>(k);
    g = k < 10 ? 1.0 : 100.0 + static_cast<double>(k);
    kinetic = sawtooth(k, 1500, 1e6);
  });
  CHECK(peaks.progress == KineticDampingProgress::Continuing);
  // Off: never a verdict.
  KineticDampingWatchOptions off;
  off.enabled = false;
  KineticDampingWatch w(-1.0, 1.0, off);
  bool any = false;
  for (long k = 1; k <= 10000; ++k)
    any = any || w.observe(k, -1.0, 1e3 * static_cast<double>(k), static_cast<double>(k)) !=
                     KineticDampingProgress::Continuing;
  CHECK_FALSE(any);
}

}  // namespace xshell::test
