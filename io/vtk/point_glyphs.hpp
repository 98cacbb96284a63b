// Internal to xshell::vtk (includes VTK headers): poly data of isolated
// points, one vertex cell each, for files whose arrays ParaView shows as
// glyphs at those points (joints, reactions).
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <vector>

namespace xshell {

// Points in double precision, in the given order: point data arrays added
// afterwards take one tuple per position.
vtkSmartPointer<vtkPolyData> point_glyphs(const std::vector<Eigen::Vector3d>& positions);

}  // namespace xshell
