// The VTK output of a real linkage, read back: counts, material frames, and
// d2 equal to the joint normal on every terminal edge.
#include <doctest/doctest.h>
#include <vtkPointData.h>

#include <random>

#include "finite_differences.hpp"
#include "io/vtk/linkage_snapshot.hpp"
#include "io/vtk/vtk_series.hpp"
#include "linkage/linkage_fixtures.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {

TEST_CASE(
    "VTK output of a deformed linkage: counts, orthonormal frames, d2 = joint normal at joints") {
  std::mt19937 rng(4);
  RodLinkage linkage(test::grid(3, 4, 0.4), test::test_options(RestShape::Input, 5));
  linkage.set_dofs(linkage.dofs() + test::random_vector(linkage.num_dofs(), rng, 0.02));
  const Eigen::Vector3d origin(1.0, -2.0, 0.5);
  test::ScratchDirectory dir("linkage-output");
  SeriesOptions options;
  options.every = 2;
  int checks = 0;
  {
    VtkSeries series(dir.path(), options);
    for (int step = 0; step < 5; ++step)
      series.write(linkage_snapshot(linkage, origin, step), step == 0 || step == 4);
    series.close();
  }
  // Steps 0 (forced), 2 and 4 (forced; also the second of its pair).
  const auto files = test::file_names(dir.path());
  const std::string pvd = test::file_head(dir.path() / "series.pvd");
  int step_files = 0;
  for (const std::string& name : files) {
    if (name.size() < 4 || name.substr(name.size() - 4) != ".vtp") continue;
    XSHELL_COUNTED_CHECK(checks, pvd.find(name) != std::string::npos);
    ++step_files;
  }
  CHECK(step_files == 3 * 4);  // three steps, four parts

  const auto rods = test::read_polydata(dir.path() / "rods_000000.vtp");
  const auto frames = test::read_polydata(dir.path() / "frames_000000.vtp");
  const auto joints = test::read_polydata(dir.path() / "joints_000000.vtp");
  // One polyline per full rod; a shared terminal edge is drawn once.
  const int nrods = static_cast<int>(linkage.topology().rods.size());
  int nodes = 0, edges = 0;
  for (const RodChain& rod : linkage.topology().rods) {
    const int n = linkage.options().subdivisions;
    const int segments = static_cast<int>(rod.segments.size());
    edges += segments * n - (segments - 1);
    nodes += segments * n - (segments - 1) + 1;
  }
  XSHELL_COUNTED_CHECK(checks, rods->GetNumberOfCells() == nrods);
  XSHELL_COUNTED_CHECK(checks, rods->GetNumberOfPoints() == nodes);
  XSHELL_COUNTED_CHECK(checks, frames->GetNumberOfPoints() == edges);
  XSHELL_COUNTED_CHECK(checks, joints->GetNumberOfPoints() == linkage.num_joints());

  vtkDataArray* d1 = frames->GetPointData()->GetArray("d1");
  vtkDataArray* d2 = frames->GetPointData()->GetArray("d2");
  REQUIRE(d1);
  REQUIRE(d2);
  vtkDataArray* normal = joints->GetPointData()->GetArray("normal");
  REQUIRE(normal);
  // Material frames are orthonormal.
  for (vtkIdType i = 0; i < frames->GetNumberOfPoints(); ++i) {
    const Eigen::Vector3d a = test::tuple3(*d1, i), b = test::tuple3(*d2, i);
    XSHELL_COUNTED_CHECK(checks, std::abs(a.norm() - 1.0) < 1e-6);
    XSHELL_COUNTED_CHECK(checks, std::abs(b.norm() - 1.0) < 1e-6);
    XSHELL_COUNTED_CHECK(checks, std::abs(a.dot(b)) < 1e-6);
  }
  int terminal = 0;
  for (vtkIdType j = 0; j < joints->GetNumberOfPoints(); ++j) {
    double p[3];
    joints->GetPoint(j, p);
    const Eigen::Vector3d joint(p[0], p[1], p[2]), n = test::tuple3(*normal, j);
    // Terminal edges are centred on their joint: their frame point is there.
    for (vtkIdType i = 0; i < frames->GetNumberOfPoints(); ++i) {
      double q[3];
      frames->GetPoint(i, q);
      if ((Eigen::Vector3d(q[0], q[1], q[2]) - joint).norm() > 1e-9) continue;
      XSHELL_COUNTED_CHECK(checks, (test::tuple3(*d2, i) - n).norm() < 1e-6);
      ++terminal;
    }
  }
  // Every joint of this grid has two rods, each with one drawn terminal edge.
  CHECK(terminal == 2 * linkage.num_joints());
  CHECK(checks > 3 * edges);
}

}  // namespace xshell::test
