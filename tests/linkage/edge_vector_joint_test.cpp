// Edge-vector joints (joint.hpp) and the conversions between the two joint
// parametrizations (edge_vector_conversion.hpp): round trips, identical
// terminal edges, the near-parallel threshold, restores across kinds.
#include <doctest/doctest.h>

#include <filesystem>
#include <random>

#include "finite_differences.hpp"
#include "io/state_file.hpp"
#include "linkage/edge_vector_conversion.hpp"
#include "linkage/model_error.hpp"
#include "linkage_fixtures.hpp"
#include "scratch_directory.hpp"

namespace xshell::test::edge_vector_joint_test {

namespace {

Joint random_rotation_joint(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Matrix3d r = rotation_matrix(random_vector(3, rng, 2.0));
  Joint joint(random_vector(3, rng), r.col(0), r.col(1), r.col(2), 1.0, 1.0, JointKind::Rotation);
  JointParams q = joint.params();
  q.segment<3>(kOmega) = random_vector(3, rng, 1.0);
  q[kAlpha] = 0.2 + 2.7 * u(rng);
  q[kLengthA] = 0.2 + u(rng);
  q[kLengthB] = 0.2 + u(rng);
  joint.set_params(q);
  return joint;
}

// The terminal edges of both rods, both orientations, at random source
// frames, are the same for the two joints; returns the number compared.
int check_same_terminal_edges(const Joint& a, const Joint& b, std::mt19937& rng) {
  int compared = 0;
  for (int label = 0; label < 2; ++label)
    for (int sign : {-1, 1}) {
      const Eigen::Vector3d t = sign * a.tangent(label);
      const Eigen::Vector3d t_hat = (t + 0.3 * random_vector(3, rng)).normalized();
      const SourceFrame source{t_hat, any_perpendicular(t_hat)};
      const TerminalEdge<double> ea = a.terminal_edge(label, sign, source, 0.0);
      const TerminalEdge<double> eb = b.terminal_edge(label, sign, source, 0.0);
      CHECK((ea.first.values() - eb.first.values()).norm() < 1e-13);
      CHECK((ea.second.values() - eb.second.values()).norm() < 1e-13);
      CHECK(std::abs(ea.theta - eb.theta) < 1e-12);
      ++compared;
    }
  return compared;
}

}  // namespace

TEST_CASE(
    "Rotation -> edge vectors -> rotation reproduces the joint (folded) and its terminal edges") {
  std::mt19937 rng(21);
  int compared = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Joint rotation = random_rotation_joint(rng);
    const Joint edges = convert_joint(rotation, JointKind::EdgeVectors);
    REQUIRE(edges.kind() == JointKind::EdgeVectors);
    CHECK((edges.position() - rotation.position()).norm() == 0.0);
    for (int x = 0; x < 2; ++x) CHECK((edges.edge(x) - rotation.edge(x)).norm() < 1e-14);
    CHECK((edges.normal() - rotation.normal()).norm() < 1e-14);
    CHECK(edges.opening_angle() == doctest::Approx(rotation.opening_angle()).epsilon(1e-13));
    // Aligned bases: c_X = (l_X, 0, 0).
    CHECK((edges.params().segment<3>(kEdgeA) - Eigen::Vector3d(rotation.params()[kLengthA], 0, 0))
              .norm() < 1e-14);
    CHECK((edges.params().segment<3>(kEdgeB) - Eigen::Vector3d(rotation.params()[kLengthB], 0, 0))
              .norm() < 1e-14);
    compared += check_same_terminal_edges(rotation, edges, rng);

    const Joint back = convert_joint(edges, JointKind::Rotation);
    Joint folded = rotation;
    folded.fold();
    CHECK((back.params() - folded.params()).norm() < 1e-13);
    CHECK((back.reference_frame() - folded.reference_frame()).norm() < 1e-13);
    compared += check_same_terminal_edges(rotation, back, rng);
  }
  CHECK(compared == 20 * 8);
}

TEST_CASE("Edge vectors -> rotation -> edge vectors reproduces the edge vectors") {
  std::mt19937 rng(22);
  int compared = 0;
  for (int trial = 0; trial < 20; ++trial) {
    Joint edges = convert_joint(random_rotation_joint(rng), JointKind::EdgeVectors);
    // Unaligned bases and general components.
    JointParams q = edges.params();
    q.segment<6>(kEdgeA) += random_vector(6, rng, 0.1);
    edges.set_params(q);
    REQUIRE(edges.check_params(q).empty());
    const Joint rotation = convert_joint(edges, JointKind::Rotation);
    CHECK(rotation.params().segment<3>(kOmega).norm() == 0.0);
    CHECK(rotation.params()[kAlpha] == doctest::Approx(edges.opening_angle()).epsilon(1e-13));
    CHECK(rotation.params()[kLengthA] == doctest::Approx(edges.edge(0).norm()).epsilon(1e-14));
    CHECK(rotation.params()[kLengthB] == doctest::Approx(edges.edge(1).norm()).epsilon(1e-14));
    compared += check_same_terminal_edges(edges, rotation, rng);
    const Joint back = convert_joint(rotation, JointKind::EdgeVectors);
    for (int x = 0; x < 2; ++x) CHECK((back.edge(x) - edges.edge(x)).norm() < 1e-14);
    compared += check_same_terminal_edges(edges, back, rng);
  }
  CHECK(compared == 20 * 8);
}

TEST_CASE(
    "Edge-vector joints refuse nearly parallel edges, fold moves nothing, align re-expresses") {
  Joint joint = joint_from_edge_vectors(
      {Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0.5, 0)},
      JointKind::EdgeVectors);
  int checks = 0;
  for (double degrees : {0.0, 0.5, 0.99, 1.01, 3.0, 179.5, 178.9}) {
    CAPTURE(degrees);
    const double a = degrees * M_PI / 180.0;
    JointParams q = joint.params();
    // e_B in the basis of rod B = [y, -x, z]: the direction (cos a, sin a, 0).
    q.segment<3>(kEdgeB) = 0.5 * Eigen::Vector3d(std::sin(a), -std::cos(a), 0.0);
    const bool parallel = std::min(degrees, 180.0 - degrees) < kMinEdgeVectorAngleDegrees;
    CHECK(joint.check_params(q).empty() == !parallel);
    ++checks;
  }
  CHECK(checks == 7);
  JointParams zero = joint.params();
  zero.segment<3>(kEdgeA).setZero();
  CHECK_FALSE(joint.check_params(zero).empty());
  CHECK_THROWS_AS(joint_from_edge_vectors({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                           Eigen::Vector3d(1, 0.01, 0)},
                                          JointKind::EdgeVectors),
                  std::domain_error);
  // A rotation joint opened beyond pi has the normal -e_A x e_B.
  Joint over(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
             Eigen::Vector3d::UnitZ(), 1.0, 1.0);
  JointParams q = over.params();
  q[kAlpha] = 3.5;
  over.set_params(q);
  CHECK_THROWS_AS(convert_joint(over, JointKind::EdgeVectors), std::domain_error);

  std::mt19937 rng(23);
  q = joint.params();
  q.segment<6>(kEdgeA) += random_vector(6, rng, 0.2);
  joint.set_params(q);
  const Eigen::Vector3d e_a = joint.edge(0), e_b = joint.edge(1);
  joint.fold();
  CHECK(joint.params() == q);
  joint.align_reference_frame();
  CHECK((joint.edge(0) - e_a).norm() < 1e-14);
  CHECK((joint.edge(1) - e_b).norm() < 1e-14);
  CHECK(joint.params()[kEdgeA + 1] == 0.0);
  CHECK(joint.params()[kEdgeB + 2] == 0.0);
}

TEST_CASE(
    "A linkage with edge-vector joints is the same linkage, set_dofs rejects near-parallel edges") {
  int graphs = 0;
  for (const LineGraph& g : {single_x(), tee(), grid(3, 3), grid(3, 4, 0.4)}) {
    LinkageOptions options = test_options();
    const RodLinkage rotation(g, options);
    options.joint_kind = JointKind::EdgeVectors;
    RodLinkage edges(g, options);
    REQUIRE(edges.num_dofs() == rotation.num_dofs());
    CHECK(edges.energy().total() <= 1e-20 * edges.segment(0).stiffness().stretching);
    for (int s = 0; s < edges.num_segments(); ++s)
      CHECK((edges.segment(s).dofs() - rotation.segment(s).dofs()).norm() < 1e-12);
    for (int j = 0; j < edges.num_joints(); ++j) {
      CHECK(edges.joint(j).opening_angle() ==
            doctest::Approx(rotation.joint(j).opening_angle()).epsilon(1e-12));
      CHECK((edges.joint(j).normal() - rotation.joint(j).normal()).norm() < 1e-12);
    }
    // Turn e_B of joint 0 onto e_A: refused as a trial point.
    Eigen::VectorXd r = edges.dofs();
    const int o = edges.joint_dof_offset(0);
    r.segment<3>(o + kEdgeB) =
        edges.joint(0).edge_basis(1).transpose() * edges.joint(0).edge(0) * 0.7;
    CHECK_THROWS_AS(edges.set_dofs(r), std::domain_error);
    ++graphs;
  }
  CHECK(graphs == 4);
}

TEST_CASE(
    "A graph with rods within 1 degree of parallel at a joint is refused with edge-vector joints") {
  LineGraph g;
  g.vertices = {{-1, 0, 0}, {0, 0, 0}, {1, 0.005, 0}, {0.5, 1, 0}};
  g.edges = {{0, 1}, {1, 2}, {2, 3}};
  LinkageOptions options = test_options();
  CHECK_NOTHROW(RodLinkage(g, options));
  options.joint_kind = JointKind::EdgeVectors;
  CHECK_THROWS_WITH_AS(RodLinkage(g, options),
                       doctest::Contains("vertex 1: its rods are 0.286 degrees from parallel"),
                       ModelError);
}

TEST_CASE("States restore across joint kinds, in memory and through state.json") {
  std::mt19937 rng(24);
  int restores = 0;
  for (JointKind from : {JointKind::Rotation, JointKind::EdgeVectors}) {
    const JointKind to = from == JointKind::Rotation ? JointKind::EdgeVectors : JointKind::Rotation;
    LinkageOptions options = test_options(RestShape::Straight);
    options.joint_kind = from;
    RodLinkage source(grid(3, 4, 0.4), options);
    source.set_dofs(source.dofs() + random_vector(source.num_dofs(), rng, 0.03));
    options.joint_kind = to;
    RodLinkage memory(grid(3, 4, 0.4), options), file(grid(3, 4, 0.4), options);
    memory.restore(source.state());
    const ScratchDirectory dir("edge-vector-state");
    write_state((dir / "state.json").string(), source, Eigen::Vector3d::Zero());
    read_state((dir / "state.json").string(), file, Eigen::Vector3d::Zero());
    for (const RodLinkage* restored : {&memory, &file}) {
      CHECK(restored->joint(0).kind() == to);
      CHECK(restored->energy().total() == doctest::Approx(source.energy().total()).epsilon(1e-10));
      for (int s = 0; s < source.num_segments(); ++s) {
        const int nodes = 3 * source.segment(s).num_nodes();
        CHECK((restored->segment(s).dofs().head(nodes) - source.segment(s).dofs().head(nodes))
                  .norm() < 1e-12);
        for (int e = 0; e < source.segment(s).num_edges(); ++e)
          CHECK((restored->segment(s).material_frame(e).d2.values() -
                 source.segment(s).material_frame(e).d2.values())
                    .norm() < 1e-12);
      }
      ++restores;
    }
  }
  CHECK(restores == 4);
}

}  // namespace xshell::test::edge_vector_joint_test
