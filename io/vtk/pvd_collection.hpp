// The text of a ParaView collection (.pvd): an XML index of data files with a
// time step each, so that ParaView opens a whole run at once and plays it.
// Files of the same time step are told apart by `part` (ParaView groups them
// into one multiblock, one block per part) and labelled by `name`:
//
//   <VTKFile type="Collection" version="0.1" byte_order="LittleEndian">
//     <Collection>
//       <DataSet timestep="0.5" part="0" name="rods" file="rods_000001.vtp"/>
//       ...
#pragma once

#include <string>
#include <vector>

namespace xshell {

// The kinds of file of one output step; the value is the .pvd part number.
enum class VtkPart { Rods = 0, Frames = 1, Joints = 2, Solids = 3 };

// "rods", "frames", "joints", "solids": the .pvd name and file name prefix.
const char* part_name(VtkPart part);

struct PvdEntry {
  double timestep = 0.0;  // snapshot time
  VtkPart part = VtkPart::Rods;
  std::string file;  // relative to the .pvd's directory
};

// The complete .pvd document for `entries`, in their order. Timesteps are
// printed with 17 significant digits (exact round trip); file names are
// XML-escaped.
std::string pvd_text(const std::vector<PvdEntry>& entries);

}  // namespace xshell
