// The linkage energy's gradient and Hessian with edge-vector joints (docs/model.md
// sections 5.4 and 7) against finite differences, unconstrained (all 9 joint
// parameters free) and constrained (supports "orientation": directions
// fixed, lengths free), on graphs with valences 1-4; supports, weights and
// the rebase for the new kind.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "finite_differences.hpp"
#include "linkage/model_error.hpp"
#include "linkage/statics_problem.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {

struct NamedGraph {
  const char* name;
  LineGraph graph;
};

std::vector<NamedGraph> test_graphs() {
  return {{"single X (valence 1, 4)", single_x()},
          {"tee (valence 1, 3)", tee()},
          {"planar grid (valence 2, 3, 4)", grid(3, 3)},
          {"curved grid (valence 2, 3, 4)", grid(3, 4, 0.4)}};
}

// Three edges per segment (the fewest) keep the finite-difference Hessians
// of the larger grids cheap.
LinkageOptions edge_options(RestShape rest, int subdivisions = 3) {
  LinkageOptions o = test_options(rest, subdivisions);
  o.joint_kind = JointKind::EdgeVectors;
  return o;
}

StaticsSetup loaded(std::vector<VertexSupport> supports) {
  StaticsSetup setup;
  setup.supports = std::move(supports);
  setup.gravity = Eigen::Vector3d(0.3, 0.1, -9.0);
  setup.forces = {{0, Eigen::Vector3d(0.1, 0.0, -0.3)}, {1, Eigen::Vector3d(0.0, 0.2, 0.1)}};
  return setup;
}

// Finite differences of the problem's total energy over its free unknowns;
// returns the number of entries compared.
int check_problem_derivatives(const LinkageProblem& problem) {
  const Eigen::VectorXd q = problem.free_dofs();
  // One working copy moved around q (the evaluations depend on the unknowns
  // only; the branch hints of the angles stay near q).
  LinkageProblem work = problem;
  const auto f = [&](const Eigen::VectorXd& y) {
    work.set_free_dofs(y);
    return work.energy().total();
  };
  const auto grad = [&](const Eigen::VectorXd& y) {
    work.set_free_dofs(y);
    return work.free_gradient();
  };
  const Eigen::MatrixXd hess(work.free_hessian());
  CHECK((hess - hess.transpose()).cwiseAbs().maxCoeff() <= 1e-10 * hess.cwiseAbs().maxCoeff());
  const DifferenceReport rg = check_gradient(f, q, problem.free_gradient(), 1e-6);
  const DifferenceReport rh = check_hessian(grad, q, hess, 1e-6);
  CHECK(rg.scale > 0.0);
  CHECK(rg.relative_error() < 1e-6);
  CHECK(rh.relative_error() < 1e-5);
  return rg.compared + rh.compared;
}

}  // namespace

TEST_CASE(
    "Edge-vector joints: unconstrained linkage gradient and Hessian match finite differences") {
  std::mt19937 rng(31);
  int checked = 0, cases = 0;
  for (const NamedGraph& ng : test_graphs())
    for (RestShape rest : {RestShape::Input, RestShape::Straight}) {
      CAPTURE(ng.name);
      CAPTURE(std::string(rest == RestShape::Input ? "input" : "straight"));
      RodLinkage linkage(ng.graph, edge_options(rest));
      linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.03));
      linkage.update_source_frames();
      linkage.fold_joints();
      // Every joint parameter free: pin a free end's node where there is one
      // (single X, tee), else a joint's position only (no "orientation").
      const int vertex = ng.graph.vertices.size() > 5 ? 0 : 1;
      LinkageProblem problem(linkage, loaded({{vertex, {SupportDof::Position}}}));
      CHECK(problem.num_free() == linkage.num_dofs() - 3);
      checked += check_problem_derivatives(problem);
      // Away from the source-frame update.
      problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.03));
      checked += check_problem_derivatives(problem);
      cases += 2;
    }
  CHECK(cases == 16);
  CHECK(checked > 16 * 1000);
}

TEST_CASE(
    "Edge-vector joints: constrained joints (orientation supports) match finite differences") {
  std::mt19937 rng(32);
  int checked = 0, constrained = 0;
  for (const NamedGraph& ng : test_graphs()) {
    CAPTURE(ng.name);
    RodLinkage linkage(ng.graph, edge_options(RestShape::Straight));
    linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.03));
    // Every joint constrained, one also pinned.
    std::vector<VertexSupport> supports;
    for (int j = 0; j < linkage.num_joints(); ++j)
      supports.push_back({linkage.topology().joints[j].vertex, {SupportDof::Orientation}});
    supports.front().fix.push_back(SupportDof::Position);
    LinkageProblem problem(linkage, loaded(supports));
    CHECK(problem.num_free() == linkage.num_dofs() - 4 * linkage.num_joints() - 3);
    // Directions are held: only the lengths move.
    const Eigen::Vector3d t_a = problem.linkage().joint(0).tangent(0),
                          t_b = problem.linkage().joint(0).tangent(1);
    problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.03));
    CHECK((problem.linkage().joint(0).tangent(0) - t_a).norm() < 1e-14);
    CHECK((problem.linkage().joint(0).tangent(1) - t_b).norm() < 1e-14);
    problem.rebase();
    checked += check_problem_derivatives(problem);
    constrained += linkage.num_joints();
  }
  CHECK(constrained == 1 + 1 + 9 + 12);
  CHECK(checked > 4 * 500);
}

TEST_CASE("Edge-vector joints: supports, gradient weights and the velocity-preserving rebase") {
  const RodLinkage linkage(grid(3, 3, 0.3), edge_options(RestShape::Straight));
  StaticsSetup angle;
  angle.supports = {{4, {SupportDof::OpeningAngle}}};
  CHECK_THROWS_WITH_AS(LinkageProblem(linkage, angle),
                       doctest::Contains("no opening-angle unknown"), ModelError);

  // Default support: the central joint pinned and constrained.
  LinkageProblem problem(linkage, StaticsSetup{});
  CHECK(problem.default_support_vertex() == 4);
  CHECK(problem.num_free() == linkage.num_dofs() - 7);
  // Joint parameters are all force-like.
  const Eigen::VectorXd w = problem.gradient_weights();
  int joint_weights = 0;
  for (int i = 0; i < problem.num_free(); ++i) {
    const int r = problem.free_indices()[i];
    if (r >= linkage.joint_dof_offset(0)) {
      CHECK(w[i] == doctest::Approx(1.0 / problem.force_scale()));
      ++joint_weights;
    }
  }
  CHECK(joint_weights == 9 * 9 - 7);
  CHECK((problem.free_mass().array() > 0.0).all());

  // The rebase carries a velocity over: the full variables move alike.
  std::mt19937 rng(33);
  problem.set_free_dofs(problem.free_dofs() + random_vector(problem.num_free(), rng, 0.05));
  Eigen::VectorXd v = random_vector(problem.num_free(), rng);
  const double h = 1e-7;
  const auto moved = [&](const LinkageProblem& p, const Eigen::VectorXd& vel) {
    LinkageProblem copy = p;
    copy.set_free_dofs(p.free_dofs() + h * vel);
    return copy;
  };
  const LinkageProblem before = moved(problem, v);
  problem.rebase(&v);
  const LinkageProblem after = moved(problem, v);
  int frames = 0;
  for (int s = 0; s < linkage.num_segments(); ++s)
    for (int e = 0; e < linkage.segment(s).num_edges(); ++e) {
      const Eigen::Vector3d a = before.linkage().segment(s).material_frame(e).d1.values();
      const Eigen::Vector3d b = after.linkage().segment(s).material_frame(e).d1.values();
      CHECK((a - b).norm() < 1e-12);
      ++frames;
    }
  CHECK(frames == linkage.num_segments() * 3);
}

TEST_CASE("Edge-vector joints: the gradient is orthogonal to rigid motions") {
  std::mt19937 rng(34);
  RodLinkage linkage(grid(3, 4, 0.4), edge_options(RestShape::Straight));
  linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.05));
  linkage.update_source_frames();
  const Eigen::VectorXd g = linkage.gradient();
  REQUIRE(g.norm() > 0.0);
  int motions = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d w = Eigen::Vector3d::Unit(axis);
    Eigen::VectorXd translation = Eigen::VectorXd::Zero(linkage.num_dofs());
    Eigen::VectorXd rotation = Eigen::VectorXd::Zero(linkage.num_dofs());
    for (int s = 0; s < linkage.num_segments(); ++s) {
      const ElasticRod& rod = linkage.segment(s);
      for (int k = 0; k < rod.num_nodes(); ++k)
        for (int c = 0; c < 3; ++c) {
          const int r = linkage.reduced_index(s, 3 * k + c);
          if (r < 0) continue;
          translation[r] = c == axis ? 1.0 : 0.0;
          rotation[r] = w.cross(rod.nodes()[k])[c];
        }
      for (int e = 0; e < rod.num_edges(); ++e) {
        const int r = linkage.reduced_index(s, rod.theta_dof(e));
        if (r >= 0) rotation[r] = w.dot(rod.tangent(e));
      }
    }
    for (int j = 0; j < linkage.num_joints(); ++j) {
      const Joint& joint = linkage.joint(j);
      const int o = linkage.joint_dof_offset(j);
      translation[o + axis] = 1.0;
      rotation.segment<3>(o) = w.cross(joint.position());
      for (int x = 0; x < 2; ++x)
        rotation.segment<3>(o + kEdgeA + 3 * x) =
            joint.edge_basis(x).transpose() * w.cross(joint.edge(x));
    }
    CHECK(std::abs(g.dot(translation)) <= 1e-9 * g.norm() * translation.norm());
    CHECK(std::abs(g.dot(rotation)) <= 1e-9 * g.norm() * rotation.norm());
    motions += 2;
  }
  CHECK(motions == 6);
}

}  // namespace xshell::test
