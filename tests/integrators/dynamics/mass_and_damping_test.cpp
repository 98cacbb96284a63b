#include "integrators/dynamics/mass_and_damping.hpp"

#include <doctest/doctest.h>

namespace xshell::test {

namespace {

// Tridiagonal-free test matrix: diag(d) with symmetric couplings c between
// neighbours i, i+1 for even i (2x2 blocks with known eigenvalues).
Eigen::SparseMatrix<double> blocks(const Eigen::VectorXd& d, double c) {
  const int n = static_cast<int>(d.size());
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, d[i]);
  for (int i = 0; i + 1 < n; i += 2) {
    t.emplace_back(i, i + 1, c);
    t.emplace_back(i + 1, i, c);
  }
  Eigen::SparseMatrix<double> H(n, n);
  H.setFromTriplets(t.begin(), t.end());
  H.makeCompressed();
  return H;
}

}  // namespace

TEST_CASE("fictitious masses are the absolute row sums of the Hessian") {
  const Eigen::SparseMatrix<double> H = blocks(Eigen::Vector4d(2.0, -3.0, 5.0, 0.0), 0.5);
  const Eigen::VectorXd m = fictitious_mass(H);
  CHECK(m[0] == doctest::Approx(2.5));
  CHECK(m[1] == doctest::Approx(3.5));
  CHECK(m[2] == doctest::Approx(5.5));
  CHECK(m[3] == doctest::Approx(0.5));
  Eigen::SparseMatrix<double> zero(3, 3);
  CHECK(fictitious_mass(zero) == Eigen::VectorXd::Ones(3));
}

TEST_CASE("inverse iteration finds the lowest eigenvalue of (H, M)") {
  // Blocks [[d0, c], [c, d1]] / mass: with M = diag(m) constant per block the
  // eigenvalues are those of the block divided by m.
  Eigen::VectorXd d(6);
  d << 4.0, 6.0, 9.0, 9.0, 20.0, 30.0;
  const double c = 1.0;
  Eigen::VectorXd mass = Eigen::VectorXd::Constant(6, 2.0);
  const Eigen::SparseMatrix<double> H = blocks(d, c);
  // Lowest: block (4, 6, c = 1): 5 - sqrt(1 + 1) = 3.5858; / 2.
  const double expected = (5.0 - std::sqrt(2.0)) / 2.0;
  CholeskySolver solver;
  const LowestMode mode = estimate_lowest_mode(solver, H, mass, 40);
  REQUIRE(mode.ok);
  CHECK_FALSE(mode.shifted);
  CHECK(mode.iterations == 40);
  CHECK(mode.eigenvalue == doctest::Approx(expected).epsilon(1e-8));
  CHECK(automatic_damping(mode, H, mass) ==
        doctest::Approx(2.0 * std::sqrt(expected)).epsilon(1e-8));

  // Indefinite: the negative eigenvalue is found through the shift.
  Eigen::VectorXd e = d;
  e[2] = -3.0;  // block (-3, 9, c = 1): 3 - sqrt(36 + 1)
  const double negative = (3.0 - std::sqrt(37.0)) / 2.0;
  const Eigen::SparseMatrix<double> K = blocks(e, c);
  const LowestMode unstable = estimate_lowest_mode(solver, K, mass, 60);
  REQUIRE(unstable.ok);
  CHECK(unstable.shifted);
  CHECK(unstable.eigenvalue == doctest::Approx(negative).epsilon(1e-6));
  CHECK(automatic_damping(unstable, K, mass) ==
        doctest::Approx(2.0 * std::sqrt(-negative)).epsilon(1e-6));
}

TEST_CASE(
    "mode estimate: unstable and lowest stable modes, each iteration stopped once converged") {
  auto diagonal = [](std::initializer_list<double> values) {
    Eigen::VectorXd d(static_cast<Eigen::Index>(values.size()));
    Eigen::Index i = 0;
    for (double v : values) d[i++] = v;
    return blocks(d, 0.0);
  };
  const Eigen::VectorXd mass = Eigen::VectorXd::Constant(8, 0.5);
  CholeskySolver solver;

  // Positive definite, the lowest mode far below the next: the Rayleigh
  // quotient settles in a few solves.
  const Eigen::SparseMatrix<double> separated =
      diagonal({100.0, 1.0, 120.0, 140.0, 160.0, 180.0, 200.0, 220.0});
  const ModeEstimate fast = estimate_modes(solver, separated, mass, 20);
  REQUIRE(fast.lowest.ok);
  CHECK_FALSE(fast.lowest.shifted);
  CHECK(fast.unstable_modes == 0);
  CHECK(fast.lowest.eigenvalue == doctest::Approx(2.0).epsilon(1e-10));
  CHECK(fast.lowest.iterations <= 5);
  // The next mode at 1.5 times the lowest: more iterations, same accuracy.
  const Eigen::SparseMatrix<double> close =
      diagonal({3.0, 2.0, 120.0, 140.0, 160.0, 180.0, 200.0, 220.0});
  const ModeEstimate slow = estimate_modes(solver, close, mass, 40);
  REQUIRE(slow.lowest.ok);
  CHECK(slow.lowest.iterations > fast.lowest.iterations + 3);
  CHECK(slow.lowest.iterations < 40);
  CHECK(slow.lowest.eigenvalue == doctest::Approx(4.0).epsilon(1e-5));
  // With no early stop, every iteration is made.
  const ModeEstimate all = estimate_modes(solver, separated, mass, 20, {}, 4, nullptr, 0.0, 0.0);
  CHECK(all.lowest.iterations == 20);

  // Two unstable modes, then the lowest stable one. The shift s > 6 puts the
  // iteration's eigenvalues 1 / (lambda + s) close together: a relative
  // change of 1e-6 at the stop leaves errors near 1e-5 in lambda.
  const Eigen::SparseMatrix<double> saddle =
      diagonal({50.0, -1.0, 60.0, 1.0, -3.0, 70.0, 80.0, 90.0});
  const ModeEstimate modes = estimate_modes(solver, saddle, mass, 40);
  REQUIRE(modes.lowest.ok);
  CHECK(modes.lowest.shifted);
  CHECK(modes.unstable_modes == 2);
  CHECK(modes.lowest.eigenvalue == doctest::Approx(-6.0).epsilon(1e-4));
  REQUIRE(modes.stable.ok);
  CHECK(modes.stable.eigenvalue == doctest::Approx(2.0).epsilon(1e-4));
  CHECK(modes.certified_shift > 6.0);

  // Unstable modes close together (relative to the shift), as the zero
  // modes of a linkage without supports: the ones after the lowest are
  // known to be unstable after a few solves each, and their exact values
  // are not needed; the lowest and the lowest stable one still are.
  const Eigen::SparseMatrix<double> cluster =
      diagonal({50.0, -2.0, 60.0, 1.0, -3.0, -1.8, -1.6, 90.0});
  CholeskySolver counted;
  const ModeEstimate clustered = estimate_modes(counted, cluster, mass, 40);
  REQUIRE(clustered.lowest.ok);
  CHECK(clustered.unstable_modes == 4);
  CHECK(clustered.lowest.eigenvalue == doctest::Approx(-6.0).epsilon(1e-4));
  REQUIRE(clustered.stable.ok);
  CHECK(clustered.stable.eigenvalue == doctest::Approx(2.0).epsilon(1e-4));
  const long others =
      counted.stats().solves - clustered.lowest.iterations - clustered.stable.iterations;
  CHECK(others <= 3 * 7);  // each to convergence: 97
}

}  // namespace xshell::test
