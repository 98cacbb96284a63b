#include "vtk_arrays.hpp"

#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

namespace xshell {

vtkSmartPointer<vtkDoubleArray> scalar_array(const std::string& name,
                                             const std::vector<double>& values) {
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(1);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (size_t i = 0; i < values.size(); ++i) array->SetValue(static_cast<vtkIdType>(i), values[i]);
  return array;
}

vtkSmartPointer<vtkIntArray> int_array(const std::string& name, const std::vector<int>& values) {
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(1);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (size_t i = 0; i < values.size(); ++i) array->SetValue(static_cast<vtkIdType>(i), values[i]);
  return array;
}

vtkSmartPointer<vtkDoubleArray> vector_array(const std::string& name,
                                             const std::vector<Eigen::Vector3d>& values) {
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (size_t i = 0; i < values.size(); ++i)
    array->SetTuple3(static_cast<vtkIdType>(i), values[i].x(), values[i].y(), values[i].z());
  return array;
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
