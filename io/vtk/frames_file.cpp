#include "frames_file.hpp"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include "polydata_writer.hpp"
#include "vtk_arrays.hpp"

namespace xshell {

void write_frames_file(const Snapshot& snapshot, const std::filesystem::path& path,
                       const WriteOptions& options) {
  validate(snapshot);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> vertices;
  std::vector<Eigen::Vector3d> d1, d2;
  std::vector<int> rod_ids, segment_ids;
  std::vector<double> stretching, lengths;

  for (const RodSnapshot& rod : snapshot.rods) {
    for (size_t i = 0; i + 1 < rod.nodes.size(); ++i) {
      const Eigen::Vector3d midpoint = 0.5 * (rod.nodes[i] + rod.nodes[i + 1]);
      const vtkIdType id = points->InsertNextPoint(midpoint.x(), midpoint.y(), midpoint.z());
      vertices->InsertNextCell(1, &id);
      lengths.push_back((rod.nodes[i + 1] - rod.nodes[i]).norm());
      rod_ids.push_back(rod.rod_id);
    }
    d1.insert(d1.end(), rod.d1.begin(), rod.d1.end());
    d2.insert(d2.end(), rod.d2.begin(), rod.d2.end());
    segment_ids.insert(segment_ids.end(), rod.edge_segment.begin(), rod.edge_segment.end());
    stretching.insert(stretching.end(), rod.stretching_density.begin(),
                      rod.stretching_density.end());
  }

  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetVerts(vertices);
  vtkPointData* point_data = data->GetPointData();
  point_data->AddArray(vector_array("d1", d1));
  point_data->AddArray(vector_array("d2", d2));
  point_data->AddArray(int_array("rod_id", rod_ids));
  point_data->AddArray(int_array("segment_id", segment_ids));
  point_data->AddArray(scalar_array("stretching_density", stretching));
  point_data->AddArray(scalar_array("edge_length", lengths));
  point_data->SetActiveVectors("d1");
  add_units(*data, {{"stretching_density", "force"}, {"edge_length", "length"}});
  write_polydata(*data, path, options);
}

}  // namespace xshell
