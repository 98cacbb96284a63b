#include "solids_file.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>

#include "polydata_writer.hpp"
#include "section_sweep.hpp"
#include "vtk_arrays.hpp"

namespace xshell {
namespace {

// The swept surface before normals, accumulated rod after rod.
struct SweptSurface {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  std::vector<int> rod_ids;                                 // per triangle
  std::vector<double> curvature, twist, bending, twisting;  // per point

  SweptSurface() { points->SetDataTypeToDouble(); }

  vtkIdType add_point(const Eigen::Vector3d& x, const RodSnapshot& rod, size_t node) {
    curvature.push_back(rod.curvature[node]);
    twist.push_back(rod.twist[node]);
    bending.push_back(rod.bending_density[node]);
    twisting.push_back(rod.twisting_density[node]);
    return points->InsertNextPoint(x.x(), x.y(), x.z());
  }

  void add_triangle(vtkIdType a, vtkIdType b, vtkIdType c, int rod_id) {
    const vtkIdType ids[3] = {a, b, c};
    triangles->InsertNextCell(3, ids);
    rod_ids.push_back(rod_id);
  }

  // Rings around every node joined by triangle strips, closed by two fans.
  // With d1 x d2 = t and a counter-clockwise outline, the triangle
  // (ring k point j, ring k point j+1, ring k+1 point j+1) has normal
  // (e_theta) x (t) = outward radial; the first cap's fan runs clockwise
  // (normal -t), the last cap's counter-clockwise (normal +t).
  void add_rod(const RodSnapshot& rod, const SolidsOptions& options) {
    const std::vector<Eigen::Vector2d> outline =
        section_outline(rod.section, options.ellipse_sides);
    const std::vector<NodeFrame> frames = node_frames(rod);
    const vtkIdType m = static_cast<vtkIdType>(outline.size());
    const size_t n_nodes = rod.nodes.size();

    const vtkIdType first = points->GetNumberOfPoints();
    for (size_t k = 0; k < n_nodes; ++k)
      for (const Eigen::Vector2d& ab : outline)
        add_point(rod.nodes[k] + ab.x() * frames[k].d1 + ab.y() * frames[k].d2, rod, k);
    const vtkIdType start_centre = add_point(rod.nodes.front(), rod, 0);
    const vtkIdType end_centre = add_point(rod.nodes.back(), rod, n_nodes - 1);

    auto ring = [&](size_t k, vtkIdType j) {
      return first + static_cast<vtkIdType>(k) * m + (j % m);
    };
    for (size_t k = 0; k + 1 < n_nodes; ++k)
      for (vtkIdType j = 0; j < m; ++j) {
        add_triangle(ring(k, j), ring(k, j + 1), ring(k + 1, j + 1), rod.rod_id);
        add_triangle(ring(k, j), ring(k + 1, j + 1), ring(k + 1, j), rod.rod_id);
      }
    for (vtkIdType j = 0; j < m; ++j) {
      add_triangle(start_centre, ring(0, j + 1), ring(0, j), rod.rod_id);
      add_triangle(end_centre, ring(n_nodes - 1, j), ring(n_nodes - 1, j + 1), rod.rod_id);
    }
  }
};

}  // namespace

void write_solids_file(const Snapshot& snapshot, const std::filesystem::path& path,
                       const WriteOptions& options, const SolidsOptions& solids) {
  validate(snapshot);
  SweptSurface surface;
  for (const RodSnapshot& rod : snapshot.rods) surface.add_rod(rod, solids);

  vtkNew<vtkPolyData> data;
  data->SetPoints(surface.points);
  data->SetPolys(surface.triangles);
  data->GetCellData()->AddArray(int_array("rod_id", surface.rod_ids));
  vtkPointData* point_data = data->GetPointData();
  point_data->AddArray(scalar_array("curvature", surface.curvature));
  point_data->AddArray(scalar_array("twist", surface.twist));
  point_data->AddArray(scalar_array("bending_density", surface.bending));
  point_data->AddArray(scalar_array("twisting_density", surface.twisting));

  // The triangles are already consistently outward: no reordering, only
  // point normals, split at creases sharper than crease_angle.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(data);
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOff();
  normals->SplittingOn();
  normals->SetFeatureAngle(solids.crease_angle);
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->NonManifoldTraversalOff();
  normals->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  normals->Update();
  vtkPolyData* output = normals->GetOutput();
  output->GetPointData()->SetActiveScalars("bending_density");
  add_units(*output, rod_units());
  write_polydata(*output, path, options);
}

}  // namespace xshell
