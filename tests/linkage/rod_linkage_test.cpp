#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test::rod_linkage_test {

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

// Gravity-like constant forces on every full variable of every segment.
std::vector<Eigen::VectorXd> test_forces(const RodLinkage& linkage) {
  std::vector<Eigen::VectorXd> f;
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const ElasticRod& rod = linkage.segment(s);
    Eigen::VectorXd fs = Eigen::VectorXd::Zero(rod.num_dofs());
    for (int k = 0; k < rod.num_nodes(); ++k)
      fs.segment<3>(3 * k) = Eigen::Vector3d(0.1, -0.2, -0.5);
    f.push_back(fs);
  }
  return f;
}

double total_energy(const RodLinkage& linkage, const std::vector<Eigen::VectorXd>& f) {
  double e = linkage.energy().total();
  for (int s = 0; s < linkage.num_segments(); ++s) e -= f[s].dot(linkage.segment(s).dofs());
  return e;
}

int check_linkage_derivatives(const RodLinkage& linkage, double grad_tol, double hess_tol) {
  const std::vector<Eigen::VectorXd> forces = test_forces(linkage);
  const Eigen::VectorXd r = linkage.dofs();
  const auto f = [&](const Eigen::VectorXd& y) {
    RodLinkage copy = linkage;
    copy.set_dofs(y);
    return total_energy(copy, forces);
  };
  const auto g = [&](const Eigen::VectorXd& y) {
    RodLinkage copy = linkage;
    copy.set_dofs(y);
    return copy.gradient(&forces);
  };
  const Eigen::VectorXd grad = linkage.gradient(&forces);
  const Eigen::MatrixXd hess = Eigen::MatrixXd(linkage.hessian(&forces));
  CHECK((hess - hess.transpose()).cwiseAbs().maxCoeff() <= 1e-10 * hess.cwiseAbs().maxCoeff());
  const DifferenceReport rg = check_gradient(f, r, grad, 1e-6);
  const DifferenceReport rh = check_hessian(g, r, hess, 1e-6);
  CHECK(rg.scale > 0.0);
  CHECK(rg.relative_error() < grad_tol);
  CHECK(rh.relative_error() < hess_tol);
  return rg.compared + rh.compared;
}

}  // namespace

TEST_CASE("Linkage gradient and Hessian match finite differences") {
  std::mt19937 rng(42);
  int checked = 0, cases = 0;
  for (const NamedGraph& ng : test_graphs()) {
    for (RestShape rest : {RestShape::Input, RestShape::Straight}) {
      CAPTURE(ng.name);
      CAPTURE(rest == RestShape::Input ? "input" : "straight");
      RodLinkage linkage(ng.graph, test_options(rest));
      linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.03));
      // Right after updating the source frames and folding the joints...
      linkage.update_source_frames();
      linkage.fold_joints();
      checked += check_linkage_derivatives(linkage, 1e-6, 1e-5);
      // ...and away from that state (omega != 0, transported frames).
      linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.03));
      checked += check_linkage_derivatives(linkage, 1e-6, 1e-5);
      cases += 2;
    }
  }
  CHECK(cases == 16);
  CHECK(checked > 16 * 100);
}

TEST_CASE("Input rest shape: zero energy and zero gradient in the input configuration") {
  int checked = 0;
  for (const NamedGraph& ng : test_graphs()) {
    CAPTURE(ng.name);
    RodLinkage linkage(ng.graph, test_options(RestShape::Input, 5));
    const double scale = linkage.segment(0).stiffness().stretching;
    CHECK(linkage.energy().total() <= 1e-20 * scale);
    CHECK(linkage.gradient().cwiseAbs().maxCoeff() <= 1e-11 * scale);
    ++checked;
  }
  CHECK(checked == 4);
}

TEST_CASE("Joints sit on their vertices, open in (0, pi) and set d2 = n on every terminal edge") {
  for (const NamedGraph& ng : test_graphs()) {
    CAPTURE(ng.name);
    const RodLinkage linkage(ng.graph, test_options());
    int terminal_edges = 0;
    for (int j = 0; j < linkage.num_joints(); ++j) {
      const Joint& joint = linkage.joint(j);
      const int v = linkage.topology().joints[j].vertex;
      CHECK((joint.position() - ng.graph.vertices[v]).norm() < 1e-14);
      CHECK(joint.opening_angle() > 0.0);
      CHECK(joint.opening_angle() < M_PI);
    }
    for (int s = 0; s < linkage.num_segments(); ++s) {
      const SegmentTopology& seg = linkage.topology().segments[s];
      const ElasticRod& rod = linkage.segment(s);
      for (int side = 0; side < 2; ++side) {
        if (seg.joint[side] < 0) {
          const Eigen::Vector3d end = rod.nodes()[side == 0 ? 0 : rod.num_edges()];
          CHECK((end - ng.graph.vertices[seg.vertex[side]]).norm() < 1e-14);
          continue;
        }
        const int edge = side == 0 ? 0 : rod.num_edges() - 1;
        const Eigen::Vector3d d2 = rod.material_frame(edge).d2.values();
        CHECK((d2 - linkage.joint(seg.joint[side]).normal()).norm() < 1e-12);
        const Eigen::Vector3d mid = 0.5 * (rod.nodes()[edge] + rod.nodes()[edge + 1]);
        CHECK((mid - linkage.joint(seg.joint[side]).position()).norm() < 1e-14);
        ++terminal_edges;
      }
    }
    CHECK(terminal_edges > 0);
  }
}

TEST_CASE("Neighbouring joints agree: normals point the same way and angles open alike") {
  const LineGraph g = grid(4, 5, 0.3, 0.3);
  const RodLinkage linkage(g, test_options());
  int pairs = 0;
  for (const SegmentTopology& seg : linkage.topology().segments) {
    if (seg.joint[0] < 0 || seg.joint[1] < 0) continue;
    const Joint& a = linkage.joint(seg.joint[0]);
    const Joint& b = linkage.joint(seg.joint[1]);
    CHECK(a.normal().dot(b.normal()) > 0.5);
    // The segment's rod carries the same label at both of its joints.
    CHECK(seg.label[0] == seg.label[1]);
    ++pairs;
  }
  CHECK(pairs > 10);
  // A sheared planar grid: all interior angles are equal.
  const double alpha = linkage.joint(linkage.topology().joint_of_vertex[6]).opening_angle();
  for (int j = 0; j < linkage.num_joints(); ++j)
    CHECK(linkage.joint(j).opening_angle() == doctest::Approx(alpha).epsilon(0.2));
}

TEST_CASE("Updating frames and folding joints change neither configuration nor energy") {
  std::mt19937 rng(1);
  RodLinkage linkage(grid(3, 3, 0.3), test_options(RestShape::Straight));
  linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.05));
  const double e = linkage.energy().total();
  std::vector<Eigen::VectorXd> before;
  for (int s = 0; s < linkage.num_segments(); ++s) before.push_back(linkage.segment(s).dofs());
  linkage.update_source_frames();
  linkage.fold_joints();
  // Re-applying the (folded) unknowns reproduces the same rods.
  linkage.set_dofs(linkage.dofs());
  CHECK(e > 0.0);
  CHECK(linkage.energy().total() == doctest::Approx(e).epsilon(1e-12));
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const Eigen::VectorXd q = linkage.segment(s).dofs();
    const ElasticRod& rod = linkage.segment(s);
    // Node positions are identical; thetas may differ (new source frames),
    // the material frames may not.
    CHECK((q.head(3 * rod.num_nodes()) - before[s].head(3 * rod.num_nodes())).norm() < 1e-12);
  }
  for (int j = 0; j < linkage.num_joints(); ++j)
    CHECK(linkage.joint(j).params().segment<3>(kOmega).norm() == 0.0);
}

TEST_CASE("The gradient is orthogonal to rigid motions of the linkage") {
  std::mt19937 rng(8);
  RodLinkage linkage(grid(3, 4, 0.4), test_options(RestShape::Straight));
  linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.05));
  linkage.update_source_frames();
  linkage.fold_joints();
  linkage.set_dofs(linkage.dofs());
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
      const int o = linkage.joint_dof_offset(j);
      translation[o + axis] = 1.0;
      rotation.segment<3>(o) = w.cross(linkage.joint(j).position());
      rotation.segment<3>(o + kOmega) = w;
    }
    CHECK(std::abs(g.dot(translation)) <= 1e-9 * g.norm() * translation.norm());
    CHECK(std::abs(g.dot(rotation)) <= 1e-9 * g.norm() * rotation.norm());
    motions += 2;
  }
  CHECK(motions == 6);
}

}  // namespace xshell::test::rod_linkage_test

namespace xshell::test::rod_linkage_test {

TEST_CASE("A segment's velocity is the Jacobian's product and the difference of set_dofs") {
  std::mt19937 rng(5);
  int compared = 0;
  for (const NamedGraph& ng : test_graphs()) {
    for (const JointKind kind : {JointKind::Rotation, JointKind::EdgeVectors}) {
      CAPTURE(ng.name);
      LinkageOptions o = test_options(RestShape::Straight);
      o.joint_kind = kind;
      RodLinkage linkage(ng.graph, o);
      // Away from the source frames and the folded joints (omega != 0).
      linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.05));
      const Eigen::VectorXd r = linkage.dofs();
      const Eigen::VectorXd v = random_vector(linkage.num_dofs(), rng, 1.0);
      const double h = 1e-5;
      RodLinkage plus = linkage, minus = linkage;
      plus.set_dofs(r + h * v);
      minus.set_dofs(r - h * v);
      for (int s = 0; s < linkage.num_segments(); ++s) {
        const Eigen::VectorXd direct = linkage.full_velocity(s, v);
        const Eigen::VectorXd jacobian = linkage.full_velocities(s, v).col(0);
        const Eigen::VectorXd difference =
            (plus.segment(s).dofs() - minus.segment(s).dofs()) / (2.0 * h);
        CHECK((direct - jacobian).lpNorm<Eigen::Infinity>() <=
              1e-12 * jacobian.lpNorm<Eigen::Infinity>());
        // Central difference: O(h^2) of the second derivatives' scale.
        CHECK((direct - difference).lpNorm<Eigen::Infinity>() <= 1e-7);
        ++compared;
      }
    }
  }
  CHECK(compared > 20);
}

}  // namespace xshell::test::rod_linkage_test
