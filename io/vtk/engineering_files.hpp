// The VTK files of a run's engineering results (final state only; not in
// series.pvd, open them beside it):
//
// reactions.vtp  a vertex cell per supported vertex; point data
//                  vertex           int         graph vertex (0-based)
//                  reaction_force   3 x double  force on the linkage (force unit)
//                  reaction_moment  3 x double  moment about the vertex (force x length),
//                                               0 where the orientation is free
// stresses.vtp   a line cell per rod edge (a joint's shared terminal edge once per
//                segment); cell data
//                  rod_id, segment_id   int
//                  axial_force          N, tension > 0 (force unit)
//                  bending_moment1      M1 about d2 (force x length)
//                  bending_moment2      M2 about d1
//                  torque               T about the tangent
//                  axial_stress         N / A (force / length^2)
//                  bending_stress1      |M1| c1 / I_d2
//                  bending_stress2      |M2| c2 / I_d1
//                  torsional_shear      |T| / W_t
//                  max_normal_stress    largest combined |normal stress| in the section
//                  equivalent_stress    sqrt(max_normal_stress^2 + 3 torsional_shear^2)
//                  utilisation          equivalent_stress / strength (only with a strength)
// joint_forces.vtp   the joints file (joints_file.hpp) of the final state with pin_force_a,
//                pin_force_b
// modes.vtp      a polyline per segment through its nodes; point data one 3 x double
//                displacement per mode (modes_file): "mode_0", ... (lowest vibration
//                modes, M-normalized) and "buckling_mode" (K_0-normalized)
#pragma once

#include <filesystem>

#include "engineering_snapshot.hpp"
#include "write_options.hpp"

namespace xshell {

// Each throws OutputError naming `path` when it cannot be written.
void write_reactions_file(const EngineeringSnapshot& snapshot, const std::filesystem::path& path,
                          const WriteOptions& options = {});
void write_stresses_file(const EngineeringSnapshot& snapshot, const std::filesystem::path& path,
                         const WriteOptions& options = {});
void write_modes_file(const EngineeringSnapshot& snapshot, const std::filesystem::path& path,
                      const WriteOptions& options = {});

}  // namespace xshell
