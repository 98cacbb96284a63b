// Internal to xshell::vtk (includes VTK headers): what a rendered picture
// shows, as VTK actors: the drawn inputs as surfaces, tubes, spheres and
// arrows, coloured through one lookup table, and the colour bar.
#pragma once

#include <vtkActor.h>
#include <vtkLookupTable.h>
#include <vtkPolyData.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

#include "render_inputs.hpp"
#include "render_png.hpp"

namespace xshell {

// The colour array over the drawn inputs.
struct Coloring {
  std::string array;  // "" : one colour for everything
  double range[2] = {0.0, 1.0};
  std::string title;  // "name [unit]", or the name when no file gives its unit
};

// Finds options.color_array on the drawn inputs (point data first, then cell
// data). Throws InputError listing the arrays there are when none carries
// it, unless options.color_optional (then: no colour).
Coloring choose_coloring(const std::vector<RenderInput>& inputs, const RenderOptions& options);

struct Scene {
  std::vector<vtkSmartPointer<vtkPolyData>> geometry;  // what the camera fits
  std::vector<vtkSmartPointer<vtkActor>> actors;
  vtkSmartPointer<vtkScalarBarActor> color_bar;  // null without a colour array
};

// Lines as tubes, points as spheres (joints) or arrows along their
// reaction_force (reactions), sized on the bounding-box diagonal of the
// inputs: tubes 0.4% (or options.tube_radius), spheres 1.2%, the largest
// arrow 15%.
Scene build_scene(const std::vector<RenderInput>& inputs, const Coloring& coloring,
                  const RenderOptions& options);

}  // namespace xshell
