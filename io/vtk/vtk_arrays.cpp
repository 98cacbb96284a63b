#include "vtk_arrays.hpp"

#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

namespace xshell {

namespace {

template <class Array>
vtkSmartPointer<Array> named_array(const std::string& name, int components, size_t tuples) {
  auto array = vtkSmartPointer<Array>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
  return array;
}

template <class Array, class Value>
vtkSmartPointer<Array> filled_scalar_array(const std::string& name,
                                           const std::vector<Value>& values) {
  auto array = named_array<Array>(name, 1, values.size());
  for (size_t i = 0; i < values.size(); ++i) array->SetValue(static_cast<vtkIdType>(i), values[i]);
  return array;
}

template <class Array>
vtkSmartPointer<Array> filled_vector_array(const std::string& name,
                                           const std::vector<Eigen::Vector3d>& values) {
  auto array = named_array<Array>(name, 3, values.size());
  for (size_t i = 0; i < values.size(); ++i)
    array->SetTuple3(static_cast<vtkIdType>(i), values[i].x(), values[i].y(), values[i].z());
  return array;
}

}  // namespace

vtkSmartPointer<vtkDoubleArray> scalar_array(const std::string& name,
                                             const std::vector<double>& values) {
  return filled_scalar_array<vtkDoubleArray>(name, values);
}

vtkSmartPointer<vtkIntArray> int_array(const std::string& name, const std::vector<int>& values) {
  return filled_scalar_array<vtkIntArray>(name, values);
}

vtkSmartPointer<vtkDoubleArray> vector_array(const std::string& name,
                                             const std::vector<Eigen::Vector3d>& values) {
  return filled_vector_array<vtkDoubleArray>(name, values);
}

vtkSmartPointer<vtkFloatArray> float_scalar_array(const std::string& name,
                                                  const std::vector<double>& values) {
  return filled_scalar_array<vtkFloatArray>(name, values);
}

vtkSmartPointer<vtkFloatArray> float_vector_array(const std::string& name,
                                                  const std::vector<Eigen::Vector3d>& values) {
  return filled_vector_array<vtkFloatArray>(name, values);
}

void add_units(vtkPolyData& data, const ArrayUnits& units) {
  vtkNew<vtkStringArray> array;
  array->SetName("units");
  for (const auto& [name, unit] : units) array->InsertNextValue(name + "=" + unit);
  data.GetFieldData()->AddArray(array);
}

ArrayUnits rod_units() {
  return {{"curvature", "1/length"},
          {"twist", "rad/length"},
          {"bending_density", "force"},
          {"twisting_density", "force"}};
}

std::string array_unit(vtkPolyData& data, const std::string& array) {
  auto* units = vtkStringArray::SafeDownCast(data.GetFieldData()->GetAbstractArray("units"));
  if (units == nullptr) return "";
  const std::string prefix = array + "=";
  for (vtkIdType i = 0; i < units->GetNumberOfValues(); ++i) {
    const std::string& entry = units->GetValue(i);
    if (entry.compare(0, prefix.size(), prefix) == 0) return entry.substr(prefix.size());
  }
  return "";
}

}  // namespace xshell
