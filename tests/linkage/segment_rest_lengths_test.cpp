#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "linkage/model_error.hpp"
#include "linkage_fixtures.hpp"

namespace xshell::test {

TEST_CASE("Segment rest lengths measure a planar grid joint to joint") {
  const LineGraph graph = grid(3, 4);
  const RodLinkage linkage(graph, test_options(RestShape::Straight));
  const std::vector<double> lengths = linkage.segment_rest_lengths();
  REQUIRE(lengths.size() == graph.edges.size());
  for (int s = 0; s < linkage.num_segments(); ++s) {
    const SegmentTopology& seg = linkage.topology().segments[s];
    CAPTURE(s);
    CHECK(lengths[s] == doctest::Approx(seg.length).epsilon(1e-12));
  }
}

TEST_CASE("Scaled segment rest lengths stretch the stress-free drawing by the closed form") {
  // Input rest shape: the drawing is stress-free. Scaling segment s's rest
  // length by c leaves every edge at strain 1/c - 1 and everything else at
  // rest, so E = EA/2 (1/c - 1)^2 c L.
  const LineGraph graph = grid(3, 3, 0.3);
  const LinkageOptions options = test_options(RestShape::Input);
  RodLinkage linkage(graph, options);
  CHECK(linkage.energy().total() == doctest::Approx(0.0).scale(1.0));
  std::vector<double> lengths = linkage.segment_rest_lengths();
  const int s = 5;
  const double c = 1.07, L = lengths[s];
  lengths[s] *= c;
  linkage.set_segment_rest_lengths(lengths);
  const double ea = stiffness(options.material).stretching;
  const RodEnergy e = linkage.energy();
  CHECK(e.stretching ==
        doctest::Approx(0.5 * ea * (1 / c - 1) * (1 / c - 1) * c * L).epsilon(1e-10));
  CHECK(e.bending == doctest::Approx(0.0).scale(1.0));
  CHECK(e.twisting == doctest::Approx(0.0).scale(1.0));
  CHECK(linkage.segment_rest_lengths()[s] == doctest::Approx(c * L).epsilon(1e-14));
  CHECK(linkage.options().segment_rest_lengths == lengths);
}

TEST_CASE("Segment rest lengths given in the options equal those set afterwards") {
  const LineGraph graph = single_x();
  RodLinkage drawn(graph, test_options(RestShape::Straight));
  std::vector<double> lengths = drawn.segment_rest_lengths();
  for (std::size_t s = 0; s < lengths.size(); ++s) lengths[s] *= 1.0 + 0.03 * double(s);
  drawn.set_segment_rest_lengths(lengths);
  LinkageOptions options = test_options(RestShape::Straight);
  options.segment_rest_lengths = lengths;
  const RodLinkage given(graph, options);
  for (int s = 0; s < given.num_segments(); ++s)
    for (std::size_t j = 0; j < given.segment(s).rest_lengths().size(); ++j)
      CHECK(given.segment(s).rest_lengths()[j] ==
            doctest::Approx(drawn.segment(s).rest_lengths()[j]).epsilon(1e-14));
  CHECK(given.energy().total() == doctest::Approx(drawn.energy().total()).epsilon(1e-12));
  CHECK(given.energy().stretching > 0.0);
}

TEST_CASE("Bad segment rest lengths are refused with the segment named") {
  const LineGraph graph = single_x();
  RodLinkage linkage(graph, test_options());
  const std::vector<double> good = linkage.segment_rest_lengths();
  CHECK_THROWS_WITH_AS(linkage.set_segment_rest_lengths({1.0, 1.0}),
                       "segment rest lengths: 2 given for 4 segments", ModelError);
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    std::vector<double> lengths = good;
    lengths[2] = bad;
    CHECK_THROWS_AS(linkage.set_segment_rest_lengths(lengths), ModelError);
  }
  LinkageOptions options = test_options();
  options.segment_rest_lengths = {1.0};
  CHECK_THROWS_AS(RodLinkage(graph, options), ModelError);
  CHECK(linkage.segment_rest_lengths() == good);
}

}  // namespace xshell::test
