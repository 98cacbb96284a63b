#include "snapshot.hpp"

#include <stdexcept>

namespace xshell {

void validate(const Snapshot& snapshot) {
  for (const RodSnapshot& rod : snapshot.rods) {
    const size_t n_nodes = rod.nodes.size();
    if (n_nodes < 2) throw std::invalid_argument("snapshot: a rod needs at least two nodes");
    const size_t n_edges = n_nodes - 1;
    auto check = [&](size_t size, size_t expected, const char* what) {
      if (size != expected)
        throw std::invalid_argument(std::string("snapshot: rod ") + std::to_string(rod.rod_id) +
                                    " has " + std::to_string(size) + " " + what +
                                    " entries, expected " + std::to_string(expected));
    };
    check(rod.edge_segment.size(), n_edges, "edge_segment");
    check(rod.d1.size(), n_edges, "d1");
    check(rod.d2.size(), n_edges, "d2");
    check(rod.stretching_density.size(), n_edges, "stretching_density");
    check(rod.curvature.size(), n_nodes, "curvature");
    check(rod.twist.size(), n_nodes, "twist");
    check(rod.bending_density.size(), n_nodes, "bending_density");
    check(rod.twisting_density.size(), n_nodes, "twisting_density");
  }
}

}  // namespace xshell
