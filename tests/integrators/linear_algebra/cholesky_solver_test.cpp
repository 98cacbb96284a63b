#include "integrators/linear_algebra/cholesky_solver.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include "integrators/linear_algebra/cholesky_pattern.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"

namespace xshell::test {

using xshell::CholeskySolver;
using xshell::FactorizationStatus;

namespace {

// A random sparse symmetric matrix with both triangles stored: a random
// pattern with ~`per_column` off-diagonal entries per column, diagonal
// `diagonal_boost` + the row's absolute sum (strictly diagonally dominant,
// hence SPD, when diagonal_boost > 0).
Eigen::SparseMatrix<double> random_symmetric(int n, int per_column, double diagonal_boost,
                                             unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> row(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < per_column; ++k) {
      const int i = row(rng);
      if (i == j) continue;
      const double v = value(rng);
      entries.emplace_back(i, j, v);
      entries.emplace_back(j, i, v);
      row_sum[i] += std::abs(v);
      row_sum[j] += std::abs(v);
    }
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, row_sum[i] + diagonal_boost);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  return A;
}

// G^-1 P S P^T G^-T, column by column, for the factor G
// of the matrix last factorized by `solver`.
Eigen::MatrixXd standard_form(CholeskySolver& solver, const Eigen::SparseMatrix<double>& S) {
  const Eigen::Index n = S.rows();
  Eigen::MatrixXd C(n, n);
  Eigen::VectorXd x(n), column(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, j);
    solver.solve_upper(e.data(), x.data());
    const Eigen::VectorXd y = S * x;
    solver.solve_lower(y.data(), column.data());
    C.col(j) = column;
  }
  return C;
}

}  // namespace

TEST_CASE("CholeskySolver solves a random SPD system and reuses its analysis") {
  const int n = 400;
  Eigen::SparseMatrix<double> A = random_symmetric(n, 4, 0.1, 7);
  std::mt19937 rng(8);
  std::normal_distribution<double> normal;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = normal(rng);

  CholeskySolver solver;
  REQUIRE(solver.factorize(A) == FactorizationStatus::PositiveDefinite);
  const Eigen::VectorXd x = solver.solve(b);
  const double residual = (A * x - b).norm() / b.norm();
  INFO("relative residual " << residual);
  CHECK(residual < 1e-10);
  CHECK(solver.stats().analyses == 1);

  // Same pattern, new values: numeric factorization only.
  const int refactorizations = 5;
  for (int k = 0; k < refactorizations; ++k) {
    Eigen::SparseMatrix<double> B = A;
    for (int j = 0; j < n; ++j) B.coeffRef(j, j) += 0.5 * (k + 1);
    REQUIRE(solver.factorize(B) == FactorizationStatus::PositiveDefinite);
    const Eigen::VectorXd y = solver.solve(b);
    CHECK((B * y - b).norm() / b.norm() < 1e-10);
  }
  CHECK(solver.stats().analyses == 1);
  CHECK(solver.stats().factorizations == 1 + refactorizations);
  CHECK(solver.stats().solves == 1 + refactorizations);

  // A diagonal shift through the same pattern equals factorizing A + D.
  const Eigen::VectorXd shift = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  REQUIRE(solver.factorize(A, &shift) == FactorizationStatus::PositiveDefinite);
  Eigen::SparseMatrix<double> shifted = A;
  for (int j = 0; j < n; ++j) shifted.coeffRef(j, j) += shift[j];
  CHECK((shifted * solver.solve(b) - b).norm() / b.norm() < 1e-10);
  CHECK(solver.stats().analyses == 1);

  // A new pattern triggers a new analysis.
  Eigen::SparseMatrix<double> C = random_symmetric(n, 5, 0.1, 9);
  REQUIRE(solver.factorize(C) == FactorizationStatus::PositiveDefinite);
  CHECK((C * solver.solve(b) - b).norm() / b.norm() < 1e-10);
  CHECK(solver.stats().analyses == 2);
}

// The matrices of this case have patterns of their own (seeds 61-64): the
// process-wide list of recent patterns holds none of them at the start.
TEST_CASE("Solvers of one pattern share its analysis and factorize as a solver of its own") {
  const int n = 300;
  const Eigen::SparseMatrix<double> A = random_symmetric(n, 4, 0.1, 61);
  Eigen::SparseMatrix<double> B = A;
  for (int j = 0; j < n; ++j) B.coeffRef(j, j) += 0.25 * (j % 3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);

  CholeskySolver first;
  REQUIRE(first.factorize(A) == FactorizationStatus::PositiveDefinite);
  CHECK(first.stats().reused_patterns == 0);
  CholeskySolver second;
  REQUIRE(second.factorize(B) == FactorizationStatus::PositiveDefinite);
  CHECK(second.stats().analyses == 1);
  CHECK(second.stats().reused_patterns == 1);
  // The same ordering, hence the same factor: the same solution, bit for bit.
  const Eigen::VectorXd shared = second.solve(b);
  REQUIRE(first.factorize(B) == FactorizationStatus::PositiveDefinite);
  CHECK(first.solve(b) == shared);
  CHECK((B * shared - b).norm() / b.norm() < 1e-10);

  // kRecentPatterns newer patterns push A's out of the list; the solvers
  // analysed for it keep it.
  CholeskySolver other;
  for (unsigned seed = 62; seed < 62 + xshell::kRecentPatterns; ++seed)
    REQUIRE(other.factorize(random_symmetric(n, 4, 0.1, seed)) ==
            FactorizationStatus::PositiveDefinite);
  CHECK(other.stats().reused_patterns == 0);
  CholeskySolver late;
  REQUIRE(late.factorize(A) == FactorizationStatus::PositiveDefinite);
  CHECK(late.stats().reused_patterns == 0);
  REQUIRE(second.factorize(A) == FactorizationStatus::PositiveDefinite);
  CHECK(second.stats().analyses == 1);
  CHECK(second.solve(b) == late.solve(b));
}

TEST_CASE("Solvers on several threads analyse and share one new pattern safely") {
  const int n = 250;
  const Eigen::SparseMatrix<double> A = random_symmetric(n, 4, 0.1, 71);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  std::vector<double> residuals(4, 1.0);
  std::vector<std::thread> threads;
  for (size_t k = 0; k < residuals.size(); ++k)
    threads.emplace_back([&, k] {
      for (int repeat = 0; repeat < 3; ++repeat) {
        CholeskySolver solver;
        if (solver.factorize(A) != FactorizationStatus::PositiveDefinite) return;
        residuals[k] =
            std::max(repeat == 0 ? 0.0 : residuals[k], (A * solver.solve(b) - b).norm() / b.norm());
      }
    });
  for (std::thread& t : threads) t.join();
  for (double r : residuals) CHECK(r < 1e-10);
}

// A sparse matrix and a dense one, the second also shifted.
TEST_CASE("The factor's halves: A^-1 in two solves, and the standard form of S phi = mu A phi") {
  const int n = 120;
  Eigen::SparseMatrix<double> dense_pattern =
      Eigen::MatrixXd::Random(n, n).sparseView() * 0.1 + random_symmetric(n, 2, 0.5, 21);
  dense_pattern = Eigen::SparseMatrix<double>(dense_pattern.transpose()) + dense_pattern;
  const Eigen::MatrixXd dense = Eigen::MatrixXd(dense_pattern);
  Eigen::SparseMatrix<double> spd =
      (dense * dense.transpose() + n * Eigen::MatrixXd::Identity(n, n)).sparseView();
  const Eigen::SparseMatrix<double> S = random_symmetric(n, 3, -4.0, 22);  // indefinite
  const Eigen::VectorXd shift = Eigen::VectorXd::LinSpaced(n, 0.5, 1.0);
  struct Case {
    const char* name;
    Eigen::SparseMatrix<double> A;
    const Eigen::VectorXd* shift;
  };
  const Case cases[] = {{"sparse", random_symmetric(n, 1, 0.2, 23), nullptr},
                        {"dense", spd, nullptr},
                        {"dense, shifted", spd, &shift}};
  for (const Case& c : cases) {
    CAPTURE(c.name);
    CholeskySolver solver;
    REQUIRE(solver.factorize(c.A, c.shift) == FactorizationStatus::PositiveDefinite);
    Eigen::MatrixXd A = Eigen::MatrixXd(c.A);
    if (c.shift) A += c.shift->asDiagonal();
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    Eigen::VectorXd half(n), x(n);
    solver.solve_lower(b.data(), half.data());
    solver.solve_upper(half.data(), x.data());
    CHECK((A * x - b).norm() / b.norm() < 1e-10);
    // G^-1 P A P^T G^-T is the identity (A shifted).
    const Eigen::SparseMatrix<double> factorized = A.sparseView();
    CHECK((standard_form(solver, factorized) - Eigen::MatrixXd::Identity(n, n)).norm() < 1e-10);
    // The standard form is symmetric, with the generalized eigenvalues.
    const Eigen::MatrixXd C = standard_form(solver, S);
    CHECK((C - C.transpose()).norm() < 1e-10 * C.norm());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> standard(0.5 * (C + C.transpose()));
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> generalized(Eigen::MatrixXd(S), A);
    CHECK((standard.eigenvalues() - generalized.eigenvalues()).norm() <
          1e-10 * generalized.eigenvalues().norm());
  }
}

TEST_CASE("The same matrix factorized again costs no factorization, any other value does") {
  const int n = 200;
  const Eigen::SparseMatrix<double> A = random_symmetric(n, 4, 0.1, 41);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd shift = Eigen::VectorXd::Constant(n, 0.5);
  CholeskySolver solver;
  REQUIRE(solver.factorize(A) == FactorizationStatus::PositiveDefinite);
  // A again, and A plus a zero shift: the same values.
  REQUIRE(solver.factorize(A) == FactorizationStatus::PositiveDefinite);
  REQUIRE(solver.factorize(A, &zero) == FactorizationStatus::PositiveDefinite);
  CHECK(solver.stats().factorizations == 1);
  CHECK((A * solver.solve(b) - b).norm() / b.norm() < 1e-10);
  // A shifted, then A: two more, each solving its own matrix.
  REQUIRE(solver.factorize(A, &shift) == FactorizationStatus::PositiveDefinite);
  Eigen::SparseMatrix<double> shifted = A;
  for (int j = 0; j < n; ++j) shifted.coeffRef(j, j) += 0.5;
  CHECK((shifted * solver.solve(b) - b).norm() / b.norm() < 1e-10);
  REQUIRE(solver.factorize(A) == FactorizationStatus::PositiveDefinite);
  CHECK((A * solver.solve(b) - b).norm() / b.norm() < 1e-10);
  CHECK(solver.stats().factorizations == 3);
  // One entry changed in its last bit is another matrix.
  Eigen::SparseMatrix<double> nudged = A;
  nudged.coeffRef(n - 1, n - 1) = std::nextafter(A.coeff(n - 1, n - 1), 1e300);
  REQUIRE(solver.factorize(nudged) == FactorizationStatus::PositiveDefinite);
  CHECK(solver.stats().factorizations == 4);
  // An indefinite matrix stays indefinite, counted once, and not solvable.
  shift.setConstant(-1e6);
  CHECK(solver.factorize(A, &shift) == FactorizationStatus::NotPositiveDefinite);
  CHECK(solver.factorize(A, &shift) == FactorizationStatus::NotPositiveDefinite);
  CHECK_FALSE(solver.factorized());
  CHECK(solver.stats().factorizations == 5);
  CHECK(solver.stats().failed_factorizations == 1);
}

TEST_CASE("CholeskySolver reports indefinite and non-finite matrices") {
  const int n = 50;
  Eigen::SparseMatrix<double> A = random_symmetric(n, 3, 0.1, 11);
  CholeskySolver solver;
  REQUIRE(solver.factorize(A) == FactorizationStatus::PositiveDefinite);

  // One negative eigenvalue direction: flip a diagonal entry.
  Eigen::SparseMatrix<double> indefinite = A;
  indefinite.coeffRef(17, 17) = -indefinite.coeff(17, 17);
  CHECK(solver.factorize(indefinite) == FactorizationStatus::NotPositiveDefinite);
  CHECK_FALSE(solver.factorized());
  CHECK_THROWS_AS(solver.solve(Eigen::VectorXd::Ones(n)), std::logic_error);
  CHECK(solver.stats().failed_factorizations == 1);

  // A singular (positive semi-definite) matrix is not positive definite either.
  Eigen::SparseMatrix<double> singular(2, 2);
  singular.insert(0, 0) = 1.0;
  singular.insert(0, 1) = 1.0;
  singular.insert(1, 0) = 1.0;
  singular.insert(1, 1) = 1.0;
  singular.makeCompressed();
  CholeskySolver small;
  CHECK(small.factorize(singular) == FactorizationStatus::NotPositiveDefinite);

  Eigen::SparseMatrix<double> nan = A;
  nan.coeffRef(3, 3) = std::nan("");
  CHECK(solver.factorize(nan) == FactorizationStatus::NonFinite);

  // The factor object survives failures: the original matrix factorizes again.
  REQUIRE(solver.factorize(A) == FactorizationStatus::PositiveDefinite);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  CHECK((A * solver.solve(b) - b).norm() < 1e-10);
  CHECK(solver.stats().analyses == 1);
}

TEST_CASE("factorize_with_shift makes an indefinite Hessian positive definite") {
  const int n = 30;
  Eigen::SparseMatrix<double> H = random_symmetric(n, 2, 0.5, 13);
  H.coeffRef(5, 5) = -2.0;  // indefinite
  const Eigen::VectorXd mass = Eigen::VectorXd::LinSpaced(n, 1.0, 3.0);
  CholeskySolver solver;
  const xshell::ShiftedFactorization f = xshell::factorize_with_shift(solver, H, mass);
  REQUIRE(f.status == FactorizationStatus::PositiveDefinite);
  CHECK(f.shifted);
  CHECK(f.tau > 0.0);
  CHECK(f.factorizations >= 2);
  CHECK(f.factorizations == solver.stats().factorizations);
  // The shift is the smallest of the tau sequence that works: tau/4 fails.
  Eigen::VectorXd smaller = (f.shift / 4.0) * mass;
  CHECK(solver.factorize(H, &smaller) == FactorizationStatus::NotPositiveDefinite);
  CHECK_FALSE(xshell::is_positive_definite(solver, H));

  Eigen::SparseMatrix<double> spd = random_symmetric(n, 2, 0.5, 14);
  const xshell::ShiftedFactorization g = xshell::factorize_with_shift(solver, spd, mass);
  CHECK(g.status == FactorizationStatus::PositiveDefinite);
  CHECK_FALSE(g.shifted);
  CHECK(g.factorizations == 1);
}

TEST_CASE("A shift memory starts the next search one step below the last shift") {
  const int n = 30;
  Eigen::SparseMatrix<double> H = random_symmetric(n, 2, 0.5, 13);
  H.coeffRef(5, 5) = -2.0;
  const Eigen::VectorXd mass = Eigen::VectorXd::LinSpaced(n, 1.0, 3.0);
  const xshell::ShiftOptions options;
  xshell::ShiftMemory memory(options);
  CHECK(memory.first_tau() == 0.0);
  CholeskySolver solver;
  const xshell::ShiftedFactorization cold =
      xshell::factorize_with_shift(solver, H, mass, options, memory.first_tau());
  REQUIRE(cold.status == FactorizationStatus::PositiveDefinite);
  memory.record(cold);
  CHECK(memory.first_tau() == doctest::Approx(cold.tau / options.growth));
  // The same Hessian again: the unshifted attempt, tau/4 (fails), tau.
  const xshell::ShiftedFactorization warm =
      xshell::factorize_with_shift(solver, H, mass, options, memory.first_tau());
  REQUIRE(warm.status == FactorizationStatus::PositiveDefinite);
  CHECK(warm.tau == doctest::Approx(cold.tau));
  CHECK(warm.factorizations == 3);
  CHECK(cold.factorizations > 3);
  // A definite matrix fades the memory by one growth factor.
  memory.record(xshell::factorize_with_shift(solver, random_symmetric(n, 2, 0.5, 14), mass, options,
                                             memory.first_tau()));
  CHECK(memory.first_tau() == doctest::Approx(cold.tau / (options.growth * options.growth)));
}

namespace {

// diag(1, ..., 1, lowest) with a unit mass: the shift needed is -lowest
// (|H| / |M| is within 2% of 1).
Eigen::SparseMatrix<double> diagonal_with_lowest(int n, double lowest) {
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  d[n - 1] = lowest;
  return Eigen::SparseMatrix<double>(d.asDiagonal());
}

// Repeats the memory's warm-started factorization of H; returns the last.
xshell::ShiftedFactorization repeat_with_memory(const Eigen::SparseMatrix<double>& H,
                                                const xshell::ShiftOptions& options,
                                                xshell::ShiftMemory& memory, int times) {
  CholeskySolver solver;
  const Eigen::VectorXd mass = Eigen::VectorXd::Ones(H.rows());
  xshell::ShiftedFactorization f;
  for (int k = 0; k < times; ++k) {
    f = xshell::factorize_with_shift(solver, H, mass, options, memory.first_tau());
    REQUIRE(f.status == FactorizationStatus::PositiveDefinite);
    memory.record(f);
  }
  return f;
}

}  // namespace

TEST_CASE("A shift memory walks down to just above a tiny negative eigenvalue") {
  const xshell::ShiftOptions options;
  const double lowest = -1e-10;  // 100 times below initial_tau
  const Eigen::SparseMatrix<double> H = diagonal_with_lowest(50, lowest);
  xshell::ShiftMemory memory(options);
  const xshell::ShiftedFactorization first = repeat_with_memory(H, options, memory, 1);
  CHECK(first.tau == options.initial_tau);
  CHECK(first.factorizations == 2);
  // One growth factor per repetition, then each tries the next one down
  // (which fails) and the one that works: within a growth factor of -lowest.
  const xshell::ShiftedFactorization settled = repeat_with_memory(H, options, memory, 8);
  CHECK(settled.shift > -lowest);
  CHECK(settled.shift <= -options.growth * lowest);
  CHECK(settled.factorizations == 3);
  // H definite again: the memory below initial_tau is forgotten.
  CHECK_FALSE(repeat_with_memory(diagonal_with_lowest(50, 1.0), options, memory, 1).shifted);
  CHECK(memory.first_tau() == 0.0);
}

TEST_CASE("A shift memory never starts below smallest_tau, even where any shift works") {
  const xshell::ShiftOptions options;
  // Singular (a mechanism): LL^T fails, every positive shift succeeds.
  const Eigen::SparseMatrix<double> H = diagonal_with_lowest(50, 0.0);
  xshell::ShiftMemory memory(options);
  const xshell::ShiftedFactorization last = repeat_with_memory(H, options, memory, 40);
  CHECK(last.tau == doctest::Approx(options.smallest_tau));
  CHECK(last.factorizations == 2);
}

}  // namespace xshell::test
