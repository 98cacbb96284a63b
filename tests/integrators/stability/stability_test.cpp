#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>

#include "integrators/beam_fixtures.hpp"
#include "integrators/common/linkage_objective.hpp"
#include "integrators/deployment/constrained_newton.hpp"
#include "integrators/deployment/deployment_fixtures.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/stability/stability_analysis.hpp"

namespace xshell::test {

namespace {

// Lateral deflection of the column's nodes in a mode, normalized to 1 at
// the tip, against the clamped-free buckling shape 1 - cos(pi s / 2L), s from
// the clamped vertex (the first node lies half an edge before it). The
// square section buckles in any plane through the axis (a double
// eigenvalue): the deflection is read along the tip's own direction.
double shape_error(const LinkageProblem& problem, const Eigen::VectorXd& mode, int& compared) {
  const auto d = node_displacements(problem, mode)[0];
  const auto& nodes = problem.linkage().segment(0).nodes();
  const double root = problem.vertex_positions()[0].x();
  const Eigen::Vector3d tip(0.0, d.back().y(), d.back().z());
  REQUIRE(tip.norm() > 0.0);
  const Eigen::Vector3d u = tip / tip.norm();
  double error = 0.0;
  for (size_t k = 0; k < d.size(); ++k) {
    const double s = nodes[k].x() - root;
    error = std::max(error, std::abs(d[k].dot(u) / tip.norm() - (1.0 - std::cos(0.5 * M_PI * s))));
    const Eigen::Vector3d lateral(0.0, d[k].y(), d[k].z());
    CHECK(lateral.cross(u).norm() <= 1e-6 * tip.norm());  // in one plane through the axis
    ++compared;
  }
  return error;
}

}  // namespace

TEST_CASE("Lowest eigenpairs by shift-invert Lanczos match a dense solve, also when indefinite") {
  int checked = 0;
  for (double factor : {0.5, 1.3}) {  // below and above the critical load: PD, then indefinite
    CAPTURE(factor);
    const double p_cr = M_PI * M_PI / 4.0;
    LinkageProblem problem = cantilever_beam(60, Eigen::Vector3d(-factor * p_cr, 0, 0));
    REQUIRE(relax(problem, 1e-9, /*escape=*/false).converged());  // straight, the saddle above P_cr
    const Eigen::SparseMatrix<double> H = problem.free_hessian();
    const Eigen::VectorXd m = problem.free_mass();
    EigenModesOptions options;
    options.count = 4;
    const EigenModes modes = lowest_eigenmodes(H, m, options);
    REQUIRE(modes.converged);
    REQUIRE(H.rows() > 4 * options.count + 20);  // the Lanczos path, not the dense fallback
    const Eigen::VectorXd r = m.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd A = r.asDiagonal() * Eigen::MatrixXd(H) * r.asDiagonal();
    const Eigen::VectorXd exact = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A).eigenvalues();
    const double scale = exact.cwiseAbs().maxCoeff();
    for (int k = 0; k < options.count; ++k) {
      CAPTURE(exact[k]);
      CHECK(std::abs(modes.values[k] - exact[k]) <= 1e-7 * std::abs(exact[k]) + 1e-14 * scale);
      const Eigen::VectorXd phi = modes.vectors.col(k);
      CHECK((H * phi - modes.values[k] * m.cwiseProduct(phi)).norm() <= 1e-6 * scale * phi.norm());
      CHECK(phi.dot(m.cwiseProduct(phi)) == doctest::Approx(1.0));
      ++checked;
    }
    CHECK((modes.values[0] < 0.0) == (factor > 1.0));
  }
  CHECK(checked == 8);
}

TEST_CASE(
    "Euler column: the linearized buckling load factor predicts P_cr, the mode is the Euler "
    "shape") {
  // Clamped-free column, E I = 1, L = 1: P_cr = pi^2 / 4, mode 1 - cos(pi s / 2).
  const double p_cr = M_PI * M_PI / 4.0;
  int compared = 0;
  for (double factor : {0.3, 0.8}) {
    CAPTURE(factor);
    LinkageProblem problem = cantilever_beam(200, Eigen::Vector3d(-factor * p_cr, 0, 0));
    REQUIRE(relax(problem, 1e-8).converged());
    const StabilityAnalysis a = analyse_stability(problem);
    REQUIRE(a.unloaded_converged);
    REQUIRE(a.buckling.status == BucklingStatus::Found);
    const double predicted = a.buckling.load_factor * factor * p_cr;
    MESSAGE("predicted P_cr / exact = " << predicted / p_cr);
    CHECK(std::abs(predicted / p_cr - 1.0) < 1e-3);
    CHECK(shape_error(problem, a.buckling.mode, compared) < 0.01);
    // The loaded structure is still stable, its lowest eigenvalue positive.
    REQUIRE(a.modes.converged);
    CHECK(a.modes.values[0] > 0.0);
    CHECK(shape_error(problem, a.modes.vectors.col(0), compared) < 0.05);
  }
  CHECK(compared == 4 * 201);
}

TEST_CASE("A tension load never buckles, without loads there is no buckling analysis") {
  LinkageProblem pulled = cantilever_beam(30, Eigen::Vector3d(2.0, 0, 0));
  REQUIRE(relax(pulled).converged());
  CHECK(analyse_stability(pulled).buckling.status == BucklingStatus::NoBuckling);
  LinkageProblem free = cantilever_beam(30, Eigen::Vector3d::Zero());
  const StabilityAnalysis a = analyse_stability(free);
  CHECK(!a.loaded);
  CHECK(a.modes.converged);
  CHECK(a.modes.values.size() == 6);
}

TEST_CASE("Buckling told that K_0 is positive definite skips only that factorization") {
  // The column at half its Euler load: lambda = 2 either way, one factorization fewer.
  const double p_cr = M_PI * M_PI / 4.0;
  LinkageProblem problem = cantilever_beam(200, Eigen::Vector3d(-0.5 * p_cr, 0, 0));
  REQUIRE(relax(problem, 1e-8).converged());
  LinkageProblem unloaded = problem;
  unloaded.scale_loads(0.0);
  REQUIRE(relax(unloaded, 1e-8).converged());
  const Eigen::SparseMatrix<double> K0 = unloaded.free_hessian(), KL = problem.free_hessian();
  CholeskySolver checked, told;
  const BucklingResult a = linearized_buckling(K0, KL, {}, &checked);
  BucklingOptions known;
  known.unloaded_positive_definite = true;
  const BucklingResult b = linearized_buckling(K0, KL, known, &told);
  REQUIRE(a.status == BucklingStatus::Found);
  REQUIRE(b.status == BucklingStatus::Found);
  CHECK(std::abs(a.load_factor / 2.0 - 1.0) < 1e-3);
  CHECK(b.load_factor == doctest::Approx(a.load_factor).epsilon(1e-12));
  CHECK(told.stats().factorizations == checked.stats().factorizations - 1);
}

}  // namespace xshell::test

namespace xshell::test {

TEST_CASE("A cantilever bent far: the linear estimate just above 1 is refuted, the column's kept") {
  // E I = 1, L = 1, a square section: a transverse tip load P L^2 / EI = 5
  // bends the cantilever far but never buckles it.
  LinkageProblem bent = cantilever_beam(40, Eigen::Vector3d(0, 0, -5.0));
  REQUIRE(relax(bent, 1e-8).converged());
  StabilityOptions unchecked;
  unchecked.check_margin = 0.0;
  const StabilityAnalysis estimate = analyse_stability(bent, unchecked);
  REQUIRE(estimate.buckling.status == BucklingStatus::Found);
  MESSAGE("linearized load factor of the bent cantilever: " << estimate.buckling.load_factor);
  CHECK(estimate.buckling.load_factor < 1.01);  // the interpolation's artifact
  CHECK(!estimate.check_factor);
  const StabilityAnalysis checked = analyse_stability(bent);
  CHECK(checked.buckling.status == BucklingStatus::Refuted);
  CHECK(std::string(buckling_status_name(checked.buckling.status)) == "refuted");
  REQUIRE(checked.check_factor);
  CHECK(*checked.check_factor == doctest::Approx(1.1 * estimate.buckling.load_factor));
  CHECK(checked.stable_at_check);
  // The Euler column's estimate survives the check: at 1.1 P_cr the
  // straight column is a saddle.
  const double p_cr = M_PI * M_PI / 4.0;
  LinkageProblem column = cantilever_beam(60, Eigen::Vector3d(-0.5 * p_cr, 0, 0));
  REQUIRE(relax(column, 1e-8).converged());
  const StabilityAnalysis euler = analyse_stability(column);
  CHECK(euler.buckling.status == BucklingStatus::Found);
  REQUIRE(euler.check_factor);
  CHECK(!euler.stable_at_check);
  CHECK(euler.buckling.load_factor * 0.5 == doctest::Approx(1.0).epsilon(2e-3));
}

TEST_CASE("The check starts from the loaded state, not from the unloaded equilibrium before it") {
  // The bent cantilever (P L^2 / EI = 5): under 1.1 lambda ~ 1.1 times its
  // load it bends a little further, its first Newton iterate within a
  // hair of the end; the unloaded equilibrium (straight) lies far away.
  LinkageProblem bent = cantilever_beam(40, Eigen::Vector3d(0, 0, -5.0));
  REQUIRE(relax(bent, 1e-8).converged());
  std::vector<double> energies;
  StabilityOptions options;
  options.on_progress = [&](const StabilityProgress& p) {
    if (p.stage == "buckling_check" && p.energy) energies.push_back(*p.energy);
  };
  const Eigen::VectorXd loaded = bent.free_dofs();
  const StabilityAnalysis a = analyse_stability(bent, options);
  REQUIRE(a.check_factor);
  REQUIRE(a.buckling.status == BucklingStatus::Refuted);
  REQUIRE(energies.size() >= 2);
  CHECK(energies.size() <= 4);
  CHECK(std::abs(energies.front() - energies.back()) <= 1e-3 * std::abs(energies.back()));
  CHECK(bent.free_dofs() == loaded);  // the caller's state is left alone
}

TEST_CASE("The analysis continues in the solve's CHOLMOD solver: the same results, no analysis") {
  // The Euler column: every stage runs (eigenmodes, the unloaded
  // equilibrium, the buckling and its check).
  const double p_cr = M_PI * M_PI / 4.0;
  LinkageProblem column = cantilever_beam(60, Eigen::Vector3d(-0.5 * p_cr, 0, 0));
  CholeskySolver solved;
  {
    LinkageObjective objective(column);
    NewtonSolver newton(objective, tight_newton(1e-8, true));
    REQUIRE(newton.solve().converged());
    newton.swap_cholesky(solved);
  }
  const CholeskyStats before = solved.stats();
  REQUIRE(before.analyses == 1);
  LinkageProblem copy = column;
  const StabilityAnalysis alone = analyse_stability(copy);
  StabilityOptions options;
  options.factorized = &solved;
  const StabilityAnalysis continued = analyse_stability(column, options);

  // The eigensolver, the buckling and the stages' Newton solves worked in
  // it (the unloaded and check solves' factorizations counted there),
  // with no symbolic analysis of their own.
  CHECK(solved.stats().analyses == 1);
  CHECK(solved.stats().solves > before.solves);
  CHECK(solved.stats().factorizations > before.factorizations);
  REQUIRE(continued.buckling.status == BucklingStatus::Found);
  CHECK(alone.buckling.status == BucklingStatus::Found);
  CHECK(continued.buckling.load_factor ==
        doctest::Approx(alone.buckling.load_factor).epsilon(1e-10));
  REQUIRE(continued.modes.values.size() == alone.modes.values.size());
  for (Eigen::Index k = 0; k < alone.modes.values.size(); ++k)
    CHECK(continued.modes.values[k] == doctest::Approx(alone.modes.values[k]).epsilon(1e-10));
  CHECK(continued.check_factor == alone.check_factor);
  CHECK(continued.stable_at_check == alone.stable_at_check);
}

namespace {

// An orthonormal basis (n x (n-1)) of the plane a . q = 0, dense.
Eigen::MatrixXd dense_null_space(const Eigen::VectorXd& a) {
  const Eigen::MatrixXd column = a;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(column);
  const Eigen::MatrixXd Q = qr.householderQ();
  return Q.rightCols(a.size() - 1);
}

}  // namespace

TEST_CASE(
    "A held deployed state: the unloaded equilibrium is held too, the buckling is the held "
    "linkage's") {
  // The 3 x 3 dome opened by 0.15 rad and held there, its corners pushed
  // towards the centre.
  const double push = 40.0;
  StaticsSetup setup;
  setup.supports = {{4, {SupportDof::Position, SupportDof::Orientation}}};
  const RodLinkage drawn(dome_grid(3, 0.8), lath_material(RestShape::Input));
  for (int corner : {0, 2, 6, 8}) {
    Eigen::Vector3d inward = -drawn.graph().vertices[corner];
    inward.z() = 0.0;
    setup.forces.push_back({corner, push * inward.normalized()});
  }
  LinkageProblem loaded(drawn, setup);
  const AverageConstraint held = average_opening_angle_constraint(loaded);
  const double opened = held.value(loaded.free_dofs()) + 0.15;
  {
    LinkageObjective objective(loaded);
    ConstrainedNewtonSolver solver(objective, held);
    REQUIRE(solver.solve(opened).converged());
  }
  // Both unloaded equilibria below, the analysis' and the independent one,
  // end with Newton's quadratic step at round-off, without chord
  // corrections (which stop just below the tolerance): the mode's
  // normalization is compared across them to 1e-8.
  StabilityOptions options;
  options.held = &held;
  options.check_margin = 0.0;
  options.unloaded_newton.max_chord_corrections = 0;
  const StabilityAnalysis a = analyse_stability(loaded, options);
  REQUIRE(a.unloaded_converged);
  REQUIRE(a.buckling.status == BucklingStatus::Found);
  MESSAGE("held load factor: " << a.buckling.load_factor);
  // The same, independently: the unloaded equilibrium at the same average,
  // both Hessians on a dense orthonormal basis of the constraint's plane.
  StaticsSetup no_loads;
  no_loads.supports = setup.supports;
  LinkageProblem unloaded(loaded.linkage(), no_loads);
  {
    LinkageObjective objective(unloaded);
    ConstrainedNewtonSolver solver(objective, held, options.unloaded_newton);
    REQUIRE(solver.solve(opened).converged());
  }
  CHECK((unloaded.free_dofs() - loaded.free_dofs()).norm() > 1e-6);  // the loads moved it
  const Eigen::MatrixXd Z = dense_null_space(held.coefficients());
  const Eigen::MatrixXd K0 = Z.transpose() * Eigen::MatrixXd(unloaded.free_hessian()) * Z;
  const Eigen::MatrixXd KL = Z.transpose() * Eigen::MatrixXd(loaded.free_hessian()) * Z;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(K0 - KL, K0);
  REQUIRE(dense.info() == Eigen::Success);
  const double nu = dense.eigenvalues().maxCoeff();
  REQUIRE(nu > 0.0);
  CHECK(a.buckling.load_factor == doctest::Approx(1.0 / nu).epsilon(1e-6));
  // The mode keeps the average, and is K_0-normalized.
  const Eigen::VectorXd& phi = a.buckling.mode;
  CHECK(std::abs(held.coefficients().dot(phi)) < 1e-10 * phi.norm());
  CHECK(phi.dot(unloaded.free_hessian() * phi) == doctest::Approx(1.0).epsilon(1e-8));
  // Without the hold, the opening mode (which the corners' push softens) is
  // part of the estimate.
  options.held = nullptr;
  const StabilityAnalysis free = analyse_stability(loaded, options);
  CHECK(free.buckling.load_factor != doctest::Approx(a.buckling.load_factor).epsilon(1e-3));
}

}  // namespace xshell::test
