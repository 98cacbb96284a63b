#include "joints_file.hpp"

#include <vtkPointData.h>

#include <cmath>

#include "point_glyphs.hpp"
#include "polydata_writer.hpp"
#include "vtk_arrays.hpp"

namespace xshell {

void write_joints_file(const Snapshot& snapshot, const std::filesystem::path& path,
                       const WriteOptions& options) {
  std::vector<Eigen::Vector3d> positions, normals;
  std::vector<int> vertex_ids, valences;
  std::vector<double> angles;
  for (const JointSnapshot& joint : snapshot.joints) {
    positions.push_back(joint.position);
    vertex_ids.push_back(joint.vertex);
    normals.push_back(joint.normal);
    angles.push_back(joint.opening_angle);
    valences.push_back(joint.valence);
  }

  const vtkSmartPointer<vtkPolyData> data = point_glyphs(positions);
  vtkPointData* point_data = data->GetPointData();
  point_data->AddArray(int_array("vertex", vertex_ids));
  point_data->AddArray(vector_array("normal", normals));
  point_data->AddArray(scalar_array("opening_angle", angles));
  point_data->AddArray(int_array("valence", valences));
  bool with_forces = !snapshot.joints.empty();
  std::vector<Eigen::Vector3d> force_a, force_b;
  for (const JointSnapshot& joint : snapshot.joints) {
    with_forces = with_forces && joint.pin_force_a && joint.pin_force_b;
    if (!with_forces) break;
    force_a.push_back(*joint.pin_force_a);
    force_b.push_back(*joint.pin_force_b);
  }
  if (with_forces) {
    point_data->AddArray(vector_array("pin_force_a", force_a));
    point_data->AddArray(vector_array("pin_force_b", force_b));
  }
  bool with_targets = false;
  std::vector<double> distances;
  for (const JointSnapshot& joint : snapshot.joints) {
    with_targets = with_targets || joint.target_distance;
    distances.push_back(joint.target_distance.value_or(std::nan("")));
  }
  if (with_targets) point_data->AddArray(scalar_array("target_distance", distances));
  point_data->SetActiveVectors("normal");
  add_units(*data, {{"opening_angle", "rad"},
                    {"pin_force_a", "force"},
                    {"pin_force_b", "force"},
                    {"target_distance", "length"}});
  write_polydata(*data, path, options);
}

}  // namespace xshell
