#include "vtk_arrays.hpp"

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

}  // namespace xshell
