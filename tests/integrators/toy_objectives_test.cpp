// The toys' derivatives against finite differences, at generic (random)
// configurations: the solver tests below rely on them being exact.
#include "toy_objectives.hpp"

#include <doctest/doctest.h>

#include <random>

namespace xshell::test {

namespace {

void perturb(xshell::Objective& objective, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Eigen::VectorXd q = objective.get();
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += u(rng);
  objective.set(q);
}

void expect_exact_derivatives(xshell::Objective& objective, const char* name) {
  const DerivativeErrors errors = check_derivatives(objective);
  INFO(name << ": gradient error " << errors.gradient << ", Hessian error " << errors.hessian);
  CHECK(errors.checked_entries == objective.size() * (objective.size() + 1));
  CHECK(errors.checked_entries > 0);
  CHECK(errors.gradient < 1e-7);
  CHECK(errors.hessian < 1e-7);
}

}  // namespace

TEST_CASE("toy objectives have exact gradients and Hessians") {
  StencilObjective chain = make_chain();
  perturb(chain, 0.02, 1);
  expect_exact_derivatives(chain, "chain");

  StencilObjective rosenbrock = make_rosenbrock(6);
  perturb(rosenbrock, 0.3, 2);
  expect_exact_derivatives(rosenbrock, "rosenbrock");

  StencilObjective column = make_column({});
  perturb(column, 0.01, 3);
  expect_exact_derivatives(column, "column");

  StencilObjective inner = make_chain();
  xshell::test::OffsetObjective offset(inner, 0.3);
  perturb(offset, 0.05, 4);
  expect_exact_derivatives(offset, "offset chain");

  SqrtWell well(Eigen::VectorXd::LinSpaced(4, 0.5, 3.0), InvalidBehaviour::Throw);
  expect_exact_derivatives(well, "sqrt well");
}

TEST_CASE("offset objective: rebase keeps the configuration and the energy") {
  StencilObjective inner = make_chain();
  xshell::test::OffsetObjective offset(inner, 0.3);
  perturb(offset, 0.05, 5);
  const Eigen::VectorXd x = offset.configuration();
  const double energy = offset.energy();
  const Eigen::VectorXd d = offset.get();
  Eigen::VectorXd velocity = Eigen::VectorXd::Ones(offset.size());
  offset.rebase(&velocity);
  CHECK(offset.get().norm() == 0.0);
  CHECK((offset.configuration() - x).norm() == 0.0);
  CHECK(offset.energy() == doctest::Approx(energy).epsilon(1e-14));
  // The velocity now describes the same motion of x: x' = (1 + 2 alpha d) d'.
  CHECK((velocity - (1.0 + 0.6 * d.array()).matrix()).norm() < 1e-14);
  CHECK(offset.rebases() == 1);
}

}  // namespace xshell::test
