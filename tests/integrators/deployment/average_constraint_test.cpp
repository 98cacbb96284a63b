#include "integrators/deployment/average_constraint.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <random>

#include "finite_differences.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/deployment/constrained_objective.hpp"
#include "integrators/deployment/deployment_fixtures.hpp"
#include "linkage/joint.hpp"

namespace xshell::test {

namespace {

// B as a dense matrix, column by column.
Eigen::MatrixXd dense_basis(const AverageConstraint& c) {
  Eigen::MatrixXd B(c.size(), c.reduced_size());
  for (Eigen::Index k = 0; k < c.reduced_size(); ++k)
    B.col(k) = c.expand(Eigen::VectorXd::Unit(c.reduced_size(), k));
  return B;
}

}  // namespace

TEST_CASE(
    "Average constraint basis: a null-space basis, its adjoint, inverse and reduced Hessian") {
  // 9 unknowns, members 1, 3, 4, 7, 8 in a tree 3 <- 1 -> 4 -> 7, 4 -> 8; one
  // more fixed quantity in the average (count 6).
  const AverageConstraint c(9, {1, 3, 4, 7, 8}, {-1, 0, 0, 2, 2}, 6, 0.3);
  const Eigen::MatrixXd B = dense_basis(c);
  std::mt19937 rng(7);
  int checks = 0;
  // a^T B = 0 and B has full column rank.
  CHECK((c.coefficients().transpose() * B).norm() < 1e-15);
  CHECK(Eigen::FullPivLU<Eigen::MatrixXd>(B).rank() == 8);
  checks += 2;
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd z = random_vector(8, rng), g = random_vector(9, rng);
    CHECK(std::abs(c.expand(z).dot(g) - z.dot(c.restrict(g))) < 1e-13);  // restrict = B^T
    CHECK((c.coordinates(c.expand(z)) - z).norm() < 1e-13);              // a left inverse
    Eigen::VectorXd q = random_vector(9, rng);
    c.project(q, 1.25);
    CHECK(c.value(q) == doctest::Approx(1.25).epsilon(1e-14));
    CHECK(c.value(q + c.expand(z)) == doctest::Approx(1.25).epsilon(1e-14));
    // The multiplier absorbs exactly the component along a.
    CHECK(std::abs(c.projected(g).dot(c.coefficients())) < 1e-14);
    CHECK(c.multiplier(2.5 * c.coefficients()) == doctest::Approx(2.5));
    checks += 6;
  }
  Eigen::MatrixXd H = Eigen::MatrixXd::Random(9, 9);
  H = (H + H.transpose()).eval();
  const Eigen::MatrixXd reduced = Eigen::MatrixXd(c.reduce(H.sparseView()));
  CHECK((reduced - B.transpose() * H * B).norm() < 1e-13 * H.norm());
  const Eigen::VectorXd m = Eigen::VectorXd::LinSpaced(9, 1.0, 2.0);
  CHECK((c.reduce_diagonal(m) - (B.transpose() * m.asDiagonal() * B).diagonal()).norm() < 1e-14);
  checks += 2;
  CHECK(checks == 34);
}

TEST_CASE(
    "Average opening angle constraint of a linkage and its null-space objective match finite "
    "differences") {
  LinkageProblem problem = dome_problem(3);
  LinkageObjective inner(problem);
  const AverageConstraint constraint = average_opening_angle_constraint(problem);
  // Every joint but none fixed: 9 members, the average is the mean alpha.
  CHECK(constraint.members().size() == 9);
  CHECK(constraint.count() == 9);
  CHECK(constraint.value(problem.free_dofs()) ==
        doctest::Approx(average_opening_angle(problem.linkage())));

  // Away from the input, at a random configuration on the constraint.
  std::mt19937 rng(11);
  Eigen::VectorXd q = problem.free_dofs() + random_vector(problem.num_free(), rng, 2e-3);
  constraint.project(q, 1.7);
  problem.set_free_dofs(q);
  ConstrainedObjective reduced(inner, constraint);
  const Eigen::VectorXd z0 = reduced.get();
  CHECK(z0.size() == problem.num_free() - 1);
  auto energy = [&](const Eigen::VectorXd& z) {
    reduced.set(z);
    return reduced.energy();
  };
  auto gradient = [&](const Eigen::VectorXd& z) {
    reduced.set(z);
    return reduced.gradient();
  };
  reduced.set(z0);
  const Eigen::VectorXd g = reduced.gradient();
  const Eigen::MatrixXd H = Eigen::MatrixXd(reduced.hessian());
  const DifferenceReport rg = check_gradient(energy, z0, g, 1e-6);
  const DifferenceReport rh = check_hessian(gradient, z0, H, 1e-6);
  reduced.set(z0);
  CAPTURE(rg.relative_error());
  CAPTURE(rh.relative_error());
  CHECK(rg.compared == z0.size());
  CHECK(rh.compared == z0.size() * z0.size());
  CHECK(rg.relative_error() < 1e-6);
  CHECK(rh.relative_error() < 1e-6);
  // Every z keeps the average.
  CHECK(constraint.value(problem.free_dofs()) == doctest::Approx(1.7).epsilon(1e-14));
  // The Hessian's pattern is that of B^T H B whatever the values.
  CHECK(reduced.hessian().nonZeros() == constraint.reduce(inner.hessian()).nonZeros());
  // The rebase moves nothing and keeps the coordinates of the opening angles.
  const double e = reduced.energy();
  Eigen::VectorXd v = random_vector(z0.size(), rng);
  const Eigen::VectorXd dq = constraint.expand(v);
  reduced.rebase(&v);
  CHECK(reduced.energy() == doctest::Approx(e).epsilon(1e-13));
  const Eigen::VectorXd dq_after = constraint.expand(v);
  int alphas = 0;
  for (int i : constraint.members()) {
    CHECK(dq_after[i] == doctest::Approx(dq[i]).epsilon(1e-12));
    ++alphas;
  }
  CHECK(alphas == 9);
}

}  // namespace xshell::test

namespace xshell::test {

TEST_CASE("The reduced Hessian's plan follows H's pattern and values, its storage reused") {
  const AverageConstraint c(9, {1, 3, 4, 7, 8}, {-1, 0, 0, 2, 2}, 6, 0.3);
  const Eigen::MatrixXd B = dense_basis(c);
  std::mt19937 rng(11);
  // Sparse symmetric H of a random pattern (density `fill`), diagonal included.
  const auto random_sparse = [&](double fill) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(9, 9);
    for (int i = 0; i < 9; ++i)
      for (int j = 0; j <= i; ++j)
        if (i == j || u(rng) < fill) H(i, j) = H(j, i) = 2.0 * u(rng) - 1.0;
    return H;
  };
  Eigen::SparseMatrix<double> out;
  int checks = 0;
  for (double fill : {0.2, 0.2, 0.6, 0.1}) {
    const Eigen::MatrixXd H = random_sparse(fill);
    Eigen::SparseMatrix<double> Hs = H.sparseView();
    Hs.makeCompressed();
    for (int values = 0; values < 2; ++values) {  // the same pattern, new values
      if (values == 1) Hs.coeffs() *= -0.5;
      const double* storage = out.valuePtr();
      const Eigen::Index nonzeros = out.nonZeros();
      c.reduce(Hs, out);
      const Eigen::MatrixXd expected = B.transpose() * Eigen::MatrixXd(Hs) * B;
      CHECK((Eigen::MatrixXd(out) - expected).norm() <= 1e-14 * (1.0 + expected.norm()));
      if (values == 1) CHECK((out.valuePtr() == storage && out.nonZeros() == nonzeros));
      CHECK((Eigen::MatrixXd(c.reduce(Hs)) - expected).norm() <= 1e-14 * (1.0 + expected.norm()));
      checks += values == 1 ? 3 : 2;
    }
  }
  CHECK(checks == 20);
  Eigen::SparseMatrix<double> wrong(8, 8);
  wrong.makeCompressed();
  CHECK_THROWS_AS(c.reduce(wrong), std::invalid_argument);
}

}  // namespace xshell::test
