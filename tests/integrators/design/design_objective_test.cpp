#include "integrators/design/design_objective.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/deployment_fixtures.hpp"
#include "linkage/model_error.hpp"

namespace xshell::test {

namespace {

// The 3 x 3 dome grid (stress-free as drawn, centre pinned) with its rest
// lengths perturbed by up to 5%, so that nothing is symmetric or at rest.
LinkageProblem perturbed_dome(std::mt19937& rng) {
  LinkageProblem problem = dome_problem(3);
  std::uniform_real_distribution<double> factor(0.95, 1.05);
  std::vector<double> p = problem.linkage().segment_rest_lengths();
  for (double& l : p) l *= factor(rng);
  problem.set_segment_rest_lengths(p);
  return problem;
}

// Terms of J: the fit alone (its gradient is all adjoint), or with the
// deployed energy and the regularization, or also the flat energy.
enum class Terms { FitOnly, Deployed, WithFlat };

DesignOptions design_options(const LinkageProblem& problem, Terms terms) {
  DesignOptions o;
  o.deployed_angle = average_opening_angle(problem.linkage()) + 0.3;
  for (int v : {0, 2, 5, 7}) {
    const Eigen::Vector3d x = problem.linkage().vertex_position(v);
    o.targets.push_back({v, x + Eigen::Vector3d(0.01 * v, -0.02, 0.05), 1.0 + 0.5 * v});
  }
  o.weights.fit = 100.0;
  o.weights.deployed_energy = terms == Terms::FitOnly ? 0.0 : 1.0;
  o.weights.flat_energy = terms == Terms::WithFlat ? 2.0 : 0.0;
  o.weights.regularization = terms == Terms::FitOnly ? 0.0 : 10.0;
  // The round-off floor of the measure on this linkage is about 6e-11.
  o.newton.gradient_tolerance = 2e-10;
  return o;
}

// The largest difference between `gradient` and central differences of J
// (steps 1e-5 p_s, every equilibrium re-solved), relative to the gradient's
// largest entry; `compared` counts the entries.
double difference_error(DesignObjective& design, const std::vector<double>& p,
                        const Eigen::VectorXd& gradient, int& compared) {
  double error = 0.0;
  for (int s = 0; s < design.num_parameters(); ++s) {
    const double h = 1e-5 * p[s];
    std::vector<double> plus = p, minus = p;
    plus[s] += h;
    minus[s] -= h;
    const DesignEvaluation ep = design.evaluate(plus), em = design.evaluate(minus);
    REQUIRE(ep.status == DesignStatus::Ok);
    REQUIRE(em.status == DesignStatus::Ok);
    error = std::max(error, std::abs((ep.value - em.value) / (2 * h) - gradient[s]));
    ++compared;
  }
  return error / gradient.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("Design objective: the adjoint gradient matches differences of re-solved equilibria") {
  std::mt19937 rng(11);
  int cases = 0;
  for (Terms terms : {Terms::FitOnly, Terms::Deployed, Terms::WithFlat}) {
    const bool with_flat = terms == Terms::WithFlat;
    const int case_number = static_cast<int>(terms);
    CAPTURE(case_number);
    const LinkageProblem problem = perturbed_dome(rng);
    DesignObjective design(problem, design_options(problem, terms));
    CHECK((design.flat() != nullptr) == with_flat);
    std::vector<double> p = design.start_lengths();
    std::uniform_real_distribution<double> factor(0.98, 1.02);
    for (double& l : p) l *= factor(rng);
    const DesignEvaluation at = design.evaluate(p);
    CAPTURE(at.reason);
    REQUIRE(at.status == DesignStatus::Ok);
    REQUIRE(at.gradient.size() == design.num_parameters());
    CHECK(at.terms.fit > 0.0);
    CHECK(at.terms.deployed_energy > 0.0);
    CHECK(at.terms.regularization > 0.0);
    CHECK((at.terms.flat_energy > 0.0) == with_flat);
    int compared = 0;
    const double relative = difference_error(design, p, at.gradient, compared);
    MESSAGE("terms " << case_number
                     << " (0 fit, 1 + deployed energy and regularization, 2 + flat "
                        "energy): dJ/dp relative error "
                     << relative);
    CHECK(relative <= 1e-6);
    CHECK(compared == 12);
    ++cases;
  }
  CHECK(cases == 3);
}

TEST_CASE(
    "Design objective: with targets moved to a surface's closest points, the gradient is exact") {
  // The surface: the tilted plane n . x = c, whose closest point is the
  // projection; every joint is attracted to it (as a target surface does).
  std::mt19937 rng(21);
  const LinkageProblem problem = perturbed_dome(rng);
  DesignOptions o = design_options(problem, Terms::FitOnly);
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const double c = 0.08;
  o.targets.clear();
  for (int v = 0; v < 9; ++v) o.targets.push_back({v, Eigen::Vector3d::Zero(), 1.0});
  int calls = 0;
  o.retarget = [&](const RodLinkage& deployed, std::vector<VertexTarget>& targets) {
    ++calls;
    for (VertexTarget& t : targets) {
      const Eigen::Vector3d x = deployed.vertex_position(t.vertex);
      t.position = x - (n.dot(x) - c) * n;
    }
  };
  DesignObjective design(problem, o);
  std::vector<double> p = design.start_lengths();
  std::uniform_real_distribution<double> factor(0.98, 1.02);
  for (double& l : p) l *= factor(rng);
  const DesignEvaluation at = design.evaluate(p);
  REQUIRE(at.status == DesignStatus::Ok);
  CHECK(calls == 1);
  // F is half the squared distances to the plane, at the new equilibrium.
  double distances = 0.0;
  for (int v = 0; v < 9; ++v)
    distances += 0.5 * std::pow(n.dot(design.deployed().linkage().vertex_position(v)) - c, 2);
  CHECK(at.terms.fit == doctest::Approx(distances).epsilon(1e-12));
  int compared = 0;
  const double relative = difference_error(design, p, at.gradient, compared);
  CHECK(compared == design.num_parameters());
  MESSAGE("surface targets: dJ/dp relative error " << relative);
  CHECK(relative <= 1e-6);
}

TEST_CASE("Design objective reports failures as a status and keeps the last equilibria") {
  std::mt19937 rng(12);
  const LinkageProblem problem = perturbed_dome(rng);
  DesignObjective design(problem, design_options(problem, Terms::WithFlat));
  const std::vector<double> p = design.start_lengths();
  const DesignEvaluation first = design.evaluate(p);
  REQUIRE(first.status == DesignStatus::Ok);
  std::vector<double> bad = p;
  bad[3] = -1.0;
  const DesignEvaluation invalid = design.evaluate(bad);
  CHECK(invalid.status == DesignStatus::InvalidLengths);
  CHECK(invalid.gradient.size() == 0);
  CHECK(design.evaluate({1.0, 2.0}).status == DesignStatus::InvalidLengths);
  const DesignEvaluation again = design.evaluate(p);
  REQUIRE(again.status == DesignStatus::Ok);
  CHECK(again.value == doctest::Approx(first.value).epsilon(1e-10));
  CHECK((again.gradient - first.gradient).norm() <= 1e-8 * first.gradient.norm());
}

TEST_CASE("Design objective refuses loads lumped on the rest lengths") {
  StaticsSetup setup;
  setup.supports = {{4, {SupportDof::Position, SupportDof::Orientation}}};
  setup.gravity = Eigen::Vector3d(0, 0, -9.81);
  LinkageOptions options = lath_material(RestShape::Input);
  options.material.density = 1800;
  const LinkageProblem loaded(RodLinkage(dome_grid(3, 0.8), options), setup);
  CHECK_THROWS_AS(DesignObjective(loaded, DesignOptions{}), ModelError);
  LinkageProblem copy = loaded;
  std::vector<double> p = copy.linkage().segment_rest_lengths();
  CHECK_THROWS_AS(copy.set_segment_rest_lengths(p), ModelError);
}

}  // namespace xshell::test
