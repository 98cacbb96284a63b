// Internal to xshell::vtk (includes VTK headers): where the camera of a
// rendered picture stands.
#pragma once

#include <vtkCamera.h>
#include <vtkPolyData.h>

#include <vector>

#include "render_png.hpp"

namespace xshell {

// Points `camera` at the centre of the bounding box of `shown` from the
// view's direction (render_png.hpp), at the nearest distance at which every
// point fits a picture of width / height `aspect` with a 5% margin
// (vtkRenderer::ResetCamera fits the bounding sphere instead, which leaves a
// flat linkage small). When the points lie nearly in a plane (their extent
// across the best-fit plane is under 5% of their largest extent along it),
// the eye is raised towards the plane's normal until it sees the plane at
// 30 degrees or more (iso), 20 or more (the other views): never edge-on.
void place_camera(vtkCamera& camera, const std::vector<vtkPolyData*>& shown, RenderView view,
                  double aspect);

}  // namespace xshell
