// Internal to xshell::vtk (includes VTK headers): named VTK data arrays built
// from the snapshot's std::vectors, one tuple per entry.
#pragma once

#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace xshell {

// One component per tuple.
vtkSmartPointer<vtkDoubleArray> scalar_array(const std::string& name,
                                             const std::vector<double>& values);
vtkSmartPointer<vtkIntArray> int_array(const std::string& name, const std::vector<int>& values);

// Three components per tuple: ParaView offers it for glyphs and as a vector.
vtkSmartPointer<vtkDoubleArray> vector_array(const std::string& name,
                                             const std::vector<Eigen::Vector3d>& values);

// The same in single precision (4 bytes a value, about 7 significant
// digits): for pictures of values that a data file carries in double (the
// solids beside the rods), half the bytes to compress and write.
vtkSmartPointer<vtkFloatArray> float_scalar_array(const std::string& name,
                                                  const std::vector<double>& values);
vtkSmartPointer<vtkFloatArray> float_vector_array(const std::string& name,
                                                  const std::vector<Eigen::Vector3d>& values);

// A unit for each named array, in the words of unit_names.hpp ("force",
// "force/length^2", "1/length", ...).
using ArrayUnits = std::vector<std::pair<std::string, std::string>>;

// Adds the field-data string array "units" to `data`: one value "NAME=UNIT"
// per entry (ParaView lists it with the file's field data).
void add_units(vtkPolyData& data, const ArrayUnits& units);

// The units of the rods' and solids' point arrays (energy per length is a
// force).
ArrayUnits rod_units();

// The unit that `data`'s field data "units" gives `array`; "" when none.
std::string array_unit(vtkPolyData& data, const std::string& array);

}  // namespace xshell
