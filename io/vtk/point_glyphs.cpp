#include "point_glyphs.hpp"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>

namespace xshell {

vtkSmartPointer<vtkPolyData> point_glyphs(const std::vector<Eigen::Vector3d>& positions) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> vertices;
  for (const Eigen::Vector3d& x : positions) {
    const vtkIdType id = points->InsertNextPoint(x.x(), x.y(), x.z());
    vertices->InsertNextCell(1, &id);
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetVerts(vertices);
  return data;
}

}  // namespace xshell
