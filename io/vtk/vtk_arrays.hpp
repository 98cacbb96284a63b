// Internal to xshell::vtk (includes VTK headers): named VTK data arrays built
// from the snapshot's std::vectors, one tuple per entry.
#pragma once

#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace xshell {

// One component per tuple.
vtkSmartPointer<vtkDoubleArray> scalar_array(const std::string& name,
                                             const std::vector<double>& values);
vtkSmartPointer<vtkIntArray> int_array(const std::string& name, const std::vector<int>& values);

// Three components per tuple: ParaView offers it for glyphs and as a vector.
vtkSmartPointer<vtkDoubleArray> vector_array(const std::string& name,
                                             const std::vector<Eigen::Vector3d>& values);

}  // namespace xshell
