// The solids file (.vtp): every rod swept by its real cross-section
// (section_sweep.hpp) into a closed triangulated surface with outward point
// normals, to look at the linkage as built (thickness, contact, how the
// sections twist) rather than as centerlines.
//
// A picture, not data: points and point data are single precision (Float32,
// about 7 significant digits; the rods file carries the same fields in
// double), which makes the file 40% smaller than in double (manta_ray's
// deployed state: 544 -> 334 kB) and quicker to compress at every step.
//
// Layout, per rod with nodes 0..n and an outline of m points:
//   points   a ring of c points around every node (node k's ring is the rod's
//            points k c .. k c + c - 1): the outline's points, a corner sharper than
//            the crease angle twice (once per side it bounds, with that
//            side's normal) so that flat faces shade flat, so c = 2m for a
//            rectangle and c = m for a smooth ellipse; then each cap's m
//            outline points and its centre (first section, then last), with
//            the cap's normal.
//   cells    2 n m side triangles and 2 m cap triangles (fans), all
//            oriented outward.
//   cell data   rod_id            int
//   point data  Normals           3 x float, unit, outward (computed from
//                                 the section and the node frame: a side's
//                                 normal, the mean of two sides' at a smooth
//                                 corner, +-t on the caps)
//               curvature, twist, bending_density, twisting_density
//                                 float, copied from the section's node, so
//                                 the solids colour like the rods file.
#pragma once

#include <filesystem>

#include "snapshot.hpp"
#include "write_options.hpp"

namespace xshell {

struct SolidsOptions {
  int ellipse_sides = 12;      // polygon sides of an elliptic section (>= 3)
  double crease_angle = 60.0;  // degrees; sharper face angles shade flat
};

// Throws std::invalid_argument for an inconsistent snapshot (see validate),
// a section with non-positive width or height, or a zero-length edge; and
// OutputError naming `path` when it cannot be written.
void write_solids_file(const Snapshot& snapshot, const std::filesystem::path& path,
                       const WriteOptions& options = {}, const SolidsOptions& solids = {});

}  // namespace xshell
