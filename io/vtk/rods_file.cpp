#include "rods_file.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include "polydata_writer.hpp"
#include "vtk_arrays.hpp"

namespace xshell {

void write_rods_file(const Snapshot& snapshot, const std::filesystem::path& path,
                     const WriteOptions& options) {
  validate(snapshot);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  std::vector<int> rod_ids, segment_ids;
  std::vector<double> curvature, twist, bending, twisting;

  for (const RodSnapshot& rod : snapshot.rods) {
    const size_t n_nodes = rod.nodes.size();
    lines->InsertNextCell(static_cast<vtkIdType>(n_nodes));
    for (size_t k = 0; k < n_nodes; ++k) {
      const Eigen::Vector3d& x = rod.nodes[k];
      lines->InsertCellPoint(points->InsertNextPoint(x.x(), x.y(), x.z()));
      segment_ids.push_back(rod.edge_segment[k == 0 ? 0 : k - 1]);
    }
    rod_ids.push_back(rod.rod_id);
    curvature.insert(curvature.end(), rod.curvature.begin(), rod.curvature.end());
    twist.insert(twist.end(), rod.twist.begin(), rod.twist.end());
    bending.insert(bending.end(), rod.bending_density.begin(), rod.bending_density.end());
    twisting.insert(twisting.end(), rod.twisting_density.begin(), rod.twisting_density.end());
  }

  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  data->GetCellData()->AddArray(int_array("rod_id", rod_ids));
  vtkPointData* point_data = data->GetPointData();
  point_data->AddArray(int_array("segment_id", segment_ids));
  point_data->AddArray(scalar_array("curvature", curvature));
  point_data->AddArray(scalar_array("twist", twist));
  point_data->AddArray(scalar_array("bending_density", bending));
  point_data->AddArray(scalar_array("twisting_density", twisting));
  point_data->SetActiveScalars("bending_density");
  add_units(*data, rod_units());
  write_polydata(*data, path, options);
}

}  // namespace xshell
