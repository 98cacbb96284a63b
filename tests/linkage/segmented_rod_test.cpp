#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

namespace {
// Rod A runs straight along x through two valence-4 joints, cut into three
// segments; short crossing rods make the joints.
LineGraph straight_rod_with_crossings() {
  LineGraph g;
  g.vertices = {{0, 0, 0},     {1, 0, 0},      {2.2, 0, 0},   {3, 0, 0},  // rod A
                {1.3, 0.8, 0}, {0.7, -0.8, 0}, {2.0, 0.9, 0}, {2.4, -0.9, 0}};
  g.edges = {{0, 1}, {1, 2}, {2, 3}, {4, 1}, {1, 5}, {6, 2}, {2, 7}};
  return g;
}

// The uncut rod through the nodes of rod A's segments, with their frames.
ElasticRod uncut_rod(const RodLinkage& linkage, const std::vector<int>& segments) {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<SourceFrame> frames;
  std::vector<double> thetas, rest;
  for (size_t k = 0; k < segments.size(); ++k) {
    const ElasticRod& rod = linkage.segment(segments[k]);
    // Consecutive segments share a terminal edge: skip the next segment's
    // first edge (and its first two nodes, already present).
    const int skip = k == 0 ? 0 : 1;
    for (int i = k == 0 ? 0 : 2; i < rod.num_nodes(); ++i) nodes.push_back(rod.nodes()[i]);
    for (int j = skip; j < rod.num_edges(); ++j) {
      frames.push_back(rod.source_frames()[j]);
      thetas.push_back(rod.thetas()[j]);
      rest.push_back(rod.rest_lengths()[j]);
    }
  }
  ElasticRod uncut(nodes, frames, thetas, linkage.segment(segments[0]).stiffness());
  uncut.set_rest_lengths(rest);
  uncut.set_rest_straight();
  return uncut;
}
}  // namespace

TEST_CASE("A straight rod cut into segments at joints has the energy of the uncut rod") {
  std::mt19937 rng(77);
  const RodLinkage reference(straight_rod_with_crossings(), test_options(RestShape::Straight, 5));
  const std::vector<int> rod_a = {0, 1, 2};
  // Rod A's segments form one rod in the topology.
  const int rod_id = reference.topology().segments[0].rod;
  CHECK(reference.topology().segments[1].rod == rod_id);
  CHECK(reference.topology().segments[2].rod == rod_id);
  int compared = 0;
  for (int trial = 0; trial < 5; ++trial) {
    RodLinkage linkage = reference;
    // Any deformation the joints allow: random reduced unknowns.
    linkage.set_dofs(linkage.dofs() + random_vector(linkage.num_dofs(), rng, 0.05));
    if (trial % 2 == 1) {
      linkage.update_source_frames();
      linkage.fold_joints();
    }
    RodEnergy segmented;
    for (int s : rod_a) segmented += linkage.segment(s).energy();
    const ElasticRod uncut = uncut_rod(linkage, rod_a);
    const RodEnergy whole = uncut.energy();
    CHECK(segmented.total() > 0.0);
    CHECK(segmented.stretching == doctest::Approx(whole.stretching).epsilon(1e-12));
    CHECK(segmented.bending == doctest::Approx(whole.bending).epsilon(1e-12));
    CHECK(segmented.twisting == doctest::Approx(whole.twisting).epsilon(1e-12));
    ++compared;
  }
  CHECK(compared == 5);
}

}  // namespace xshell::test
