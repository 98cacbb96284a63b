// Internal to xshell::vtk (includes VTK headers): the .vtp files a picture is
// made of, read and sorted by how they are drawn, and moved to an
// exaggerated deflection.
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

namespace xshell {

enum class DrawnAs {
  Surface,  // polygons (solids_*.vtp)
  Tubes,    // polylines (rods_*.vtp, stresses.vtp, modes.vtp)
  Spheres,  // points (joints_*.vtp, joint_forces.vtp, frames_*.vtp)
  Arrows,   // points with "reaction_force" (reactions.vtp)
};

struct RenderInput {
  std::string path;
  vtkSmartPointer<vtkPolyData> data;
  DrawnAs drawn = DrawnAs::Spheres;
};

// Reads `path`; throws InputError naming it when it is missing, empty, not
// VTK PolyData, truncated, malformed or has no points.
RenderInput read_render_input(const std::string& path);

// The inputs that are drawn: the surfaces when any input has polygons (the
// polylines then are the same rods), else the polylines; and every point
// file. Throws InputError when nothing has polygons, polylines or points.
std::vector<RenderInput> drawn_inputs(std::vector<RenderInput> inputs);

// The file that holds `path`'s reference geometry: PART_000000.vtp for
// PART_NNNNNN.vtp (the run's first written step), joints_000000.vtp for
// joint_forces.vtp; "" for reactions.vtp (supports are drawn where they are
// held) and for any other file.
std::string reference_file(const std::string& path);

// Moves every point of each input (but reactions) to reference + k
// (point - reference). Throws InputError when an input has no reference file
// or one with another number of points.
void scale_deflection(std::vector<RenderInput>& inputs, double k);

}  // namespace xshell
