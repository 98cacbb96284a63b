// Small snapshots for the VTK writer tests: pure functions, no I/O.
#pragma once

#include "io/vtk/snapshot.hpp"

namespace xshell::test {

// Two bent rods crossing at one joint, with twisted (but orthonormal,
// right-handed) material frames, non-constant densities, and five joints:
//   rod 7: rectangle 0.02 x 0.005, 8 edges along x, bulging in z;
//          segments 0 (edges 0-3) and 1 (edges 4-7);
//   rod 9: ellipse 0.015 x 0.008, 6 edges along y, bulging in z;
//          segments 2 (edges 0-2) and 3 (edges 3-5);
//   joints: vertex 1 at the crossing (rod 7 node 4 = rod 9 node 3, valence
//           4) and vertices 0, 2, 3, 4 at the four rod ends (valence 1).
// `time` is copied into the snapshot; `phase` bends the rods a little more
// or less so that successive steps differ.
Snapshot demo_snapshot(double time = 0.0, double phase = 0.0);

// One straight untwisted rod of `n_edges` edges from `start` to `end`, with
// the given section and d1 along an arbitrary direction orthogonal to the
// axis; one joint at each end. Its swept solid is an exact prism.
Snapshot straight_rod_snapshot(const SectionSnapshot& section, const Eigen::Vector3d& start,
                               const Eigen::Vector3d& end, int n_edges);

// A square grid linkage of side 1 in the xy plane, centred at the origin:
// `n` rods along x (ids 0 to n - 1) and `n` along y (ids n to 2n - 1),
// 10 mm x 10 mm (0.01) laths, 4 edges between crossings, raised to
// z = height (1 - 4 r^2) (r the distance from the centre: a dome for
// height > 0, a sag for height < 0); a joint at every crossing.
Snapshot grid_snapshot(int n, double height);

}  // namespace xshell::test
