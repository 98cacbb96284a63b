// The solids file (.vtp): every rod swept by its real cross-section
// (section_sweep.hpp) into a closed triangulated surface with outward point
// normals, to look at the linkage as built (thickness, contact, how the
// sections twist) rather than as centerlines.
//
// Layout, per rod with nodes 0..n and an outline of m points:
//   points   (n + 1) m ring points (ring k around node k), then the centres
//            of the first and last sections; then duplicated where the
//            surface has a crease (section corners, the caps) so that flat
//            faces shade flat (vtkPolyDataNormals splitting).
//   cells    2 n m side triangles and 2 m cap triangles (fans), all
//            oriented outward.
//   cell data   rod_id            int
//   point data  Normals           3 x double, unit, outward
//               curvature, twist, bending_density, twisting_density
//                                 double, copied from the section's node, so
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
