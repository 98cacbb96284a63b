// The fabrication files of a linkage (linkage/fabrication.hpp for what the
// data mean): cut lengths, drill stations and joint angles, for building it
// from straight laths pinned at scissor joints.
//
// Units: lengths (length, s, cross-section width and height) in the length
// unit of the linkage file, angles in radians. Vertices are OBJ vertex
// indices, 0-based in file order (as in summary.json and state.json); rods
// are numbered as the `rod_id` of the VTK files. Each file is written
// atomically (atomic_file.hpp).
//
// fabrication.json:
// {
//   "format": "xshell-fabrication", "version": 1,
//   "units": {"length": "length unit of grid.obj", "angle": "radian"},
//   "rods": [{"rod": k, "family": "A" | "B", "length": L, "closed": false,
//             "cross_section": {"shape": "rectangle" | "ellipse", "width": w, "height": h},
//             "stations": [{"kind": "end" | "joint", "vertex": v | null, "s": s}, ...],
//             "other_label_joints": [v, ...]}, ...],
//   "joints": [{"vertex": v, "valence": 2 | 3 | 4, "rods": [k_A, k_B], "stations": [s_A, s_B],
//               "angle_input": a0, "angle": a}, ...]
// }
// stations: in increasing s from the rod's start (0) to its end (L), the two
// ends included; "vertex" is null at an end that is no vertex (a rod that
// ends at a joint reaches half a terminal edge past it). A joint's "rods" are
// its rods A and B, "stations" its s on each.
//
// fabrication.csv: one row per station, rods in order, stations in
// increasing s; header `rod,family,kind,vertex,s,rod_length`: the rod, its
// family (A or B), the station's kind (end or joint), its OBJ vertex (empty
// for an end that is no vertex), its s and the rod's cut length (12
// significant digits; the JSON has every digit).
//
// fabrication.svg: the laths side by side (fabrication_svg.hpp).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/config.hpp"
#include "linkage/fabrication.hpp"

namespace xshell {

// How the files name their units.
struct FabricationUnits {
  std::string length = "length unit of the linkage file";
  std::string angle = "radian";
};

// The units of a configuration's linkage: "length unit of <its file name>".
FabricationUnits fabrication_units(const Config& config);

nlohmann::json fabrication_json(const FabricationData& data, const FabricationUnits& units);
std::string fabrication_csv(const FabricationData& data);

// Writes fabrication.json, fabrication.csv and fabrication.svg into `dir`,
// which must exist. Throws OutputError naming the file that failed.
void write_fabrication_files(const FabricationData& data, const FabricationUnits& units,
                             const std::filesystem::path& dir);

// The fabrication data of `linkage` in its current state, written as above:
// what a converged run and `xshell fabricate` write.
void write_fabrication(const RodLinkage& linkage, const FabricationUnits& units,
                       const std::filesystem::path& dir);

}  // namespace xshell
