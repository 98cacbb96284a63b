#include "solids_file.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>

#include "polydata_writer.hpp"
#include "section_sweep.hpp"
#include "vtk_arrays.hpp"

namespace xshell {
namespace {

// A point of the ring around every node: an outline point and the outward
// normal it carries in section coordinates. A corner sharper than the crease
// angle is two columns (one per side, each with its side's normal, so flat
// faces shade flat); a smooth one is one column with the mean normal.
struct RingColumn {
  Eigen::Vector2d at;
  Eigen::Vector2d normal;
};

// The columns of an outline, and for each side j (outline point j to j+1)
// the columns its start and end use.
struct RingLayout {
  std::vector<RingColumn> columns;
  std::vector<vtkIdType> side_start, side_end;
};

// Outward normal of the side from a to b of a counter-clockwise outline.
Eigen::Vector2d side_normal(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return Eigen::Vector2d(b.y() - a.y(), a.x() - b.x()).normalized();
}

RingLayout ring_layout(const std::vector<Eigen::Vector2d>& outline, double crease_degrees) {
  const size_t m = outline.size();
  std::vector<Eigen::Vector2d> sides(m);
  for (size_t j = 0; j < m; ++j) sides[j] = side_normal(outline[j], outline[(j + 1) % m]);
  const double crease_cos = std::cos(crease_degrees * M_PI / 180.0);
  RingLayout layout;
  layout.side_start.resize(m);
  layout.side_end.resize(m);
  for (size_t j = 0; j < m; ++j) {
    const size_t before = (j + m - 1) % m;  // the side ending at corner j
    const Eigen::Vector2d &in = sides[before], &out = sides[j];
    if (in.dot(out) < crease_cos) {
      layout.side_end[before] = static_cast<vtkIdType>(layout.columns.size());
      layout.columns.push_back({outline[j], in});
      layout.side_start[j] = static_cast<vtkIdType>(layout.columns.size());
      layout.columns.push_back({outline[j], out});
    } else {
      layout.side_end[before] = layout.side_start[j] =
          static_cast<vtkIdType>(layout.columns.size());
      layout.columns.push_back({outline[j], (in + out).normalized()});
    }
  }
  return layout;
}

// The swept surface with its normals, accumulated rod after rod.
struct SweptSurface {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  std::vector<Eigen::Vector3d> normals;                     // per point
  std::vector<int> rod_ids;                                 // per triangle
  std::vector<double> curvature, twist, bending, twisting;  // per point

  SweptSurface() { points->SetDataTypeToFloat(); }

  vtkIdType add_point(const Eigen::Vector3d& x, const Eigen::Vector3d& normal,
                      const RodSnapshot& rod, size_t node) {
    normals.push_back(normal);
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

  // A cap of node `k`: its outline points and centre, all with normal
  // `normal` (the cap is flat). Returns the first point's id; the centre
  // follows the m outline points.
  vtkIdType add_cap(const RodSnapshot& rod, size_t k, const NodeFrame& frame,
                    const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector3d& normal) {
    const vtkIdType first = points->GetNumberOfPoints();
    for (const Eigen::Vector2d& ab : outline)
      add_point(rod.nodes[k] + ab.x() * frame.d1 + ab.y() * frame.d2, normal, rod, k);
    add_point(rod.nodes[k], normal, rod, k);
    return first;
  }

  // Rings around every node joined by triangle strips, closed by two fans.
  // With d1 x d2 = t and a counter-clockwise outline, the triangle
  // (ring k point j, ring k point j+1, ring k+1 point j+1) has normal
  // (e_theta) x (t) = outward radial; the first cap's fan runs clockwise
  // (normal -t), the last cap's counter-clockwise (normal +t).
  void add_rod(const RodSnapshot& rod, const SolidsOptions& options) {
    const std::vector<Eigen::Vector2d> outline =
        section_outline(rod.section, options.ellipse_sides);
    const RingLayout layout = ring_layout(outline, options.crease_angle);
    const std::vector<NodeFrame> frames = node_frames(rod);
    const vtkIdType m = static_cast<vtkIdType>(outline.size());
    const vtkIdType columns = static_cast<vtkIdType>(layout.columns.size());
    const size_t n_nodes = rod.nodes.size();

    const vtkIdType first = points->GetNumberOfPoints();
    for (size_t k = 0; k < n_nodes; ++k) {
      const NodeFrame& f = frames[k];
      for (const RingColumn& c : layout.columns)
        add_point(rod.nodes[k] + c.at.x() * f.d1 + c.at.y() * f.d2,
                  c.normal.x() * f.d1 + c.normal.y() * f.d2, rod, k);
    }
    const vtkIdType start_cap = add_cap(rod, 0, frames.front(), outline, -frames.front().tangent);
    const vtkIdType end_cap =
        add_cap(rod, n_nodes - 1, frames.back(), outline, frames.back().tangent);

    auto ring = [&](size_t k, vtkIdType column) {
      return first + static_cast<vtkIdType>(k) * columns + column;
    };
    for (size_t k = 0; k + 1 < n_nodes; ++k)
      for (vtkIdType j = 0; j < m; ++j) {
        const vtkIdType a = layout.side_start[static_cast<size_t>(j)];
        const vtkIdType b = layout.side_end[static_cast<size_t>(j)];
        add_triangle(ring(k, a), ring(k, b), ring(k + 1, b), rod.rod_id);
        add_triangle(ring(k, a), ring(k + 1, b), ring(k + 1, a), rod.rod_id);
      }
    for (vtkIdType j = 0; j < m; ++j) {
      add_triangle(start_cap + m, start_cap + (j + 1) % m, start_cap + j, rod.rod_id);
      add_triangle(end_cap + m, end_cap + j, end_cap + (j + 1) % m, rod.rod_id);
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
  point_data->SetNormals(float_vector_array("Normals", surface.normals));
  point_data->AddArray(float_scalar_array("curvature", surface.curvature));
  point_data->AddArray(float_scalar_array("twist", surface.twist));
  point_data->AddArray(float_scalar_array("bending_density", surface.bending));
  point_data->AddArray(float_scalar_array("twisting_density", surface.twisting));
  point_data->SetActiveScalars("bending_density");
  add_units(*data, rod_units());
  write_polydata(*data, path, options);
}

}  // namespace xshell
