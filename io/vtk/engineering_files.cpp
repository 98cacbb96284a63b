#include "engineering_files.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <stdexcept>

#include "point_glyphs.hpp"
#include "polydata_writer.hpp"
#include "vtk_arrays.hpp"

namespace xshell {

void write_reactions_file(const EngineeringSnapshot& snapshot, const std::filesystem::path& path,
                          const WriteOptions& options) {
  std::vector<Eigen::Vector3d> positions, forces, moments;
  std::vector<int> ids;
  for (const ReactionGlyph& r : snapshot.reactions) {
    positions.push_back(r.position);
    ids.push_back(r.vertex);
    forces.push_back(r.force);
    moments.push_back(r.moment);
  }
  const vtkSmartPointer<vtkPolyData> data = point_glyphs(positions);
  vtkPointData* point_data = data->GetPointData();
  point_data->AddArray(int_array("vertex", ids));
  point_data->AddArray(vector_array("reaction_force", forces));
  point_data->AddArray(vector_array("reaction_moment", moments));
  point_data->SetActiveVectors("reaction_force");
  add_units(*data, {{"reaction_force", "force"}, {"reaction_moment", "force length"}});
  write_polydata(*data, path, options);
}

void write_stresses_file(const EngineeringSnapshot& snapshot, const std::filesystem::path& path,
                         const WriteOptions& options) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  std::vector<int> rod_ids, segment_ids;
  std::vector<double> columns[12];
  bool any_utilisation = false;
  for (const EdgeResult& e : snapshot.edges) {
    lines->InsertNextCell(2);
    lines->InsertCellPoint(points->InsertNextPoint(e.a.x(), e.a.y(), e.a.z()));
    lines->InsertCellPoint(points->InsertNextPoint(e.b.x(), e.b.y(), e.b.z()));
    rod_ids.push_back(e.rod_id);
    segment_ids.push_back(e.segment_id);
    const double values[12] = {
        e.axial_force,       e.bending_moment1,   e.bending_moment2, e.torque,
        e.axial_stress,      e.bending_stress1,   e.bending_stress2, e.torsional_shear,
        e.max_normal_stress, e.equivalent_stress, e.utilisation,     0.0};
    for (int k = 0; k < 11; ++k) columns[k].push_back(values[k]);
    any_utilisation = any_utilisation || e.utilisation >= 0.0;
  }
  static const char* names[11] = {
      "axial_force",       "bending_moment1",   "bending_moment2", "torque",
      "axial_stress",      "bending_stress1",   "bending_stress2", "torsional_shear",
      "max_normal_stress", "equivalent_stress", "utilisation"};
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  vtkCellData* cell_data = data->GetCellData();
  cell_data->AddArray(int_array("rod_id", rod_ids));
  cell_data->AddArray(int_array("segment_id", segment_ids));
  for (int k = 0; k < 11; ++k)
    if (k < 10 || any_utilisation) cell_data->AddArray(scalar_array(names[k], columns[k]));
  cell_data->SetActiveScalars(any_utilisation ? "utilisation" : "max_normal_stress");
  static const char* units[10] = {
      "force",          "force length",   "force length",   "force length",   "force/length^2",
      "force/length^2", "force/length^2", "force/length^2", "force/length^2", "force/length^2"};
  ArrayUnits stress_units;
  for (int k = 0; k < 10; ++k) stress_units.emplace_back(names[k], units[k]);
  add_units(*data, stress_units);
  write_polydata(*data, path, options);
}

void write_modes_file(const EngineeringSnapshot& snapshot, const std::filesystem::path& path,
                      const WriteOptions& options) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  for (const auto& nodes : snapshot.segment_nodes) {
    lines->InsertNextCell(static_cast<vtkIdType>(nodes.size()));
    for (const Eigen::Vector3d& x : nodes)
      lines->InsertCellPoint(points->InsertNextPoint(x.x(), x.y(), x.z()));
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  for (const ModeField& mode : snapshot.modes) {
    std::vector<Eigen::Vector3d> flat;
    for (const auto& segment : mode.displacement)
      flat.insert(flat.end(), segment.begin(), segment.end());
    if (static_cast<vtkIdType>(flat.size()) != points->GetNumberOfPoints())
      throw std::invalid_argument("modes file: mode " + mode.name +
                                  " does not match the rod nodes");
    data->GetPointData()->AddArray(vector_array(mode.name, flat));
  }
  if (!snapshot.modes.empty())
    data->GetPointData()->SetActiveVectors(snapshot.modes.front().name.c_str());
  write_polydata(*data, path, options);
}

}  // namespace xshell
