#include "io/vtk/engineering_files.hpp"

#include <vtkCellData.h>
#include <vtkPointData.h>

#include "io/vtk/joints_file.hpp"
#include "linkage/linkage_fixtures.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {

TEST_CASE("Engineering files: reactions, per-edge stresses, pin forces and modes round-trip") {
  test::ScratchDirectory dir("engineering");
  StaticsSetup setup;
  setup.gravity = Eigen::Vector3d(0, 0, -9.81);
  setup.supports = {{1, {SupportDof::Orientation}}, {2, {SupportDof::Position}}};
  LinkageOptions options = test::test_options();
  options.material.strength = 10.0;
  options.clamped_ends = clamped_free_ends(test::single_x(), setup.supports);
  const LinkageProblem problem(RodLinkage(test::single_x(), options), setup);
  EngineeringResults results;
  results.reactions = support_reactions(problem);
  results.stresses = linkage_stresses(problem.linkage());
  results.joint_forces = joint_forces(problem);
  const Eigen::Vector3d origin(1, 2, 3);
  EngineeringSnapshot snapshot = engineering_snapshot(problem.linkage(), results, origin);
  std::vector<std::vector<Eigen::Vector3d>> field;
  for (const auto& nodes : snapshot.segment_nodes)
    field.emplace_back(nodes.size(), Eigen::Vector3d(0, 0, 1));
  snapshot.modes.push_back({"mode_0", field});

  write_reactions_file(snapshot, dir.path() / "reactions.vtp");
  write_stresses_file(snapshot, dir.path() / "stresses.vtp");
  write_joints_file(snapshot.joints, dir.path() / "joint_forces.vtp");
  write_modes_file(snapshot, dir.path() / "modes.vtp");

  int checked = 0;
  const auto reactions = test::read_polydata(dir.path() / "reactions.vtp");
  XSHELL_COUNTED_CHECK(checked, reactions->GetNumberOfPoints() == 2);
  vtkDataArray* force = reactions->GetPointData()->GetArray("reaction_force");
  REQUIRE(force != nullptr);
  XSHELL_COUNTED_CHECK(checked,
                       (test::tuple3(*force, 0) - results.reactions[0].force).norm() < 1e-12);
  XSHELL_COUNTED_CHECK(checked, reactions->GetPointData()->GetArray("reaction_moment") != nullptr);

  const auto stresses = test::read_polydata(dir.path() / "stresses.vtp");
  int edges = 0;
  for (int s = 0; s < problem.linkage().num_segments(); ++s)
    edges += problem.linkage().segment(s).num_edges();
  XSHELL_COUNTED_CHECK(checked, stresses->GetNumberOfCells() == edges);
  for (const char* name : {"axial_force", "bending_moment1", "bending_moment2", "torque",
                           "axial_stress", "bending_stress1", "bending_stress2", "torsional_shear",
                           "max_normal_stress", "equivalent_stress", "utilisation"}) {
    CAPTURE(name);
    vtkDataArray* a = stresses->GetCellData()->GetArray(name);
    XSHELL_COUNTED_CHECK(checked, a != nullptr);
    if (a) XSHELL_COUNTED_CHECK(checked, a->GetNumberOfTuples() == edges);
  }
  const auto joints = test::read_polydata(dir.path() / "joint_forces.vtp");
  vtkDataArray* pin = joints->GetPointData()->GetArray("pin_force_a");
  REQUIRE(pin != nullptr);
  XSHELL_COUNTED_CHECK(
      checked, (test::tuple3(*pin, 0) - results.joint_forces[0].force_on[0]).norm() < 1e-12);
  const auto modes = test::read_polydata(dir.path() / "modes.vtp");
  vtkDataArray* mode = modes->GetPointData()->GetArray("mode_0");
  REQUIRE(mode != nullptr);
  XSHELL_COUNTED_CHECK(checked, mode->GetNumberOfTuples() == modes->GetNumberOfPoints());
  CHECK(checked == 28);
}

}  // namespace xshell::test
