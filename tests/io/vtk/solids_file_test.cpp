// The solids file: rods swept by their cross-sections into closed, outward
// oriented surfaces.
#include "io/vtk/solids_file.hpp"

#include <doctest/doctest.h>
#include <vtkCellData.h>
#include <vtkIdList.h>
#include <vtkPointData.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <map>

#include "demo_snapshot.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test::solids_file_test {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d point(vtkPolyData& data, vtkIdType id) {
  Eigen::Vector3d x;
  data.GetPoint(id, x.data());
  return x;
}

// Closed and consistently oriented: after merging coincident points (the
// file duplicates points at creases and caps), every directed edge of a
// triangle appears exactly once and its reverse exactly once. Returns the
// number of directed edges checked.
int check_closed_and_oriented(vtkPolyData& data) {
  std::map<std::array<double, 3>, int> merged;
  std::vector<int> id_of(static_cast<size_t>(data.GetNumberOfPoints()));
  for (vtkIdType p = 0; p < data.GetNumberOfPoints(); ++p) {
    const Eigen::Vector3d x = point(data, p);
    id_of[static_cast<size_t>(p)] =
        merged.emplace(std::array<double, 3>{x.x(), x.y(), x.z()}, static_cast<int>(merged.size()))
            .first->second;
  }
  std::map<std::pair<int, int>, int> directed;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < data.GetNumberOfCells(); ++c) {
    data.GetCellPoints(c, cell);
    REQUIRE(cell->GetNumberOfIds() == 3);
    for (vtkIdType j = 0; j < 3; ++j)
      ++directed[{id_of[static_cast<size_t>(cell->GetId(j))],
                  id_of[static_cast<size_t>(cell->GetId((j + 1) % 3))]}];
  }
  int checked = 0;
  for (const auto& [edge, count] : directed) {
    CHECK(count == 1);
    const auto reverse = directed.find({edge.second, edge.first});
    CHECK((reverse != directed.end() && reverse->second == 1));
    ++checked;
  }
  return checked;
}

// Divergence theorem: V = sum over triangles of p0 . (p1 x p2) / 6; positive
// for outward orientation.
double signed_volume(vtkPolyData& data) {
  double volume = 0.0;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < data.GetNumberOfCells(); ++c) {
    data.GetCellPoints(c, cell);
    volume += point(data, cell->GetId(0))
                  .dot(point(data, cell->GetId(1)).cross(point(data, cell->GetId(2)))) /
              6.0;
  }
  return volume;
}

}  // namespace

TEST_CASE("solids file: closed oriented surfaces, one triangle set per rod") {
  const Snapshot snapshot = demo_snapshot(0.0, 0.3);
  for (VtkFormat format : {VtkFormat::Binary, VtkFormat::Ascii}) {
    ScratchDirectory dir("solids");
    const auto path = dir.path() / "solids.vtp";
    write_solids_file(snapshot, path, {format}, {});
    const auto data = read_polydata(path);

    // Rod 7: rectangle (4 corners), 8 edges; rod 9: 12-gon, 6 edges.
    const vtkIdType triangles_a = 2 * 8 * 4 + 2 * 4, triangles_b = 2 * 6 * 12 + 2 * 12;
    REQUIRE(data->GetNumberOfPolys() == triangles_a + triangles_b);
    REQUIRE(data->GetNumberOfCells() == triangles_a + triangles_b);
    // Ring points and cap centres, plus the copies made at creases.
    CHECK(data->GetNumberOfPoints() >= 9 * 4 + 2 + 7 * 12 + 2);

    int checks = 0;
    vtkDataArray* rod_id = data->GetCellData()->GetArray("rod_id");
    REQUIRE(rod_id);
    for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c)
      XSHELL_COUNTED_CHECK(checks, rod_id->GetTuple1(c) == (c < triangles_a ? 7 : 9));

    vtkDataArray* normals = data->GetPointData()->GetArray("Normals");
    REQUIRE(normals);
    REQUIRE(data->GetPointData()->GetArray("bending_density"));
    for (vtkIdType p = 0; p < data->GetNumberOfPoints(); ++p)
      XSHELL_COUNTED_CHECK(checks, std::abs(tuple3(*normals, p).norm() - 1.0) < 1e-6);

    const int edges = check_closed_and_oriented(*data);
    CHECK(edges == 3 * (triangles_a + triangles_b));
    CHECK(signed_volume(*data) > 0.0);
    CHECK(checks == data->GetNumberOfCells() + data->GetNumberOfPoints());
  }
}

TEST_CASE("solids file: a straight rod is an exact prism with outward normals") {
  const Eigen::Vector3d start(0.2, -0.1, 0.4), end(1.1, 0.5, 0.1);
  const double length = (end - start).norm();
  const Eigen::Vector3d centre = 0.5 * (start + end);
  struct Case {
    SectionSnapshot section;
    double area;  // of the swept polygon
  };
  const int sides = 12;
  const Case cases[] = {
      {{SectionSnapshot::Shape::Rectangle, 0.05, 0.02}, 0.05 * 0.02},
      {{SectionSnapshot::Shape::Ellipse, 0.06, 0.03},
       0.5 * sides * 0.03 * 0.015 * std::sin(2 * kPi / sides)},
  };
  int checked_cases = 0;
  for (const Case& c : cases) {
    CAPTURE(static_cast<int>(c.section.shape));
    ScratchDirectory dir("prism");
    const auto path = dir.path() / "solids.vtp";
    write_solids_file(straight_rod_snapshot(c.section, start, end, 5), path, {}, {sides, 60.0});
    const auto data = read_polydata(path);
    // Single-precision points: relative errors of order 1e-7.
    CHECK(signed_volume(*data) == doctest::Approx(c.area * length).epsilon(1e-6));
    CHECK(check_closed_and_oriented(*data) == 3 * data->GetNumberOfCells());

    // A convex body: the outward normal at p points away from any interior
    // point, here the centre.
    vtkDataArray* normals = data->GetPointData()->GetArray("Normals");
    REQUIRE(normals);
    int outward = 0;
    for (vtkIdType p = 0; p < data->GetNumberOfPoints(); ++p)
      outward += tuple3(*normals, p).dot(point(*data, p) - centre) > 0.0;
    CHECK(outward == data->GetNumberOfPoints());
    CHECK(outward > 0);
    ++checked_cases;
  }
  CHECK(checked_cases == 2);
}

// The largest angle (radians) between a triangle's face normal and the
// point normals of its corners, over all triangles.
double largest_normal_deviation(vtkPolyData& data) {
  vtkDataArray* normals = data.GetPointData()->GetArray("Normals");
  REQUIRE(normals);
  double largest = 0.0;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < data.GetNumberOfCells(); ++c) {
    data.GetCellPoints(c, cell);
    const Eigen::Vector3d a = point(data, cell->GetId(0)), b = point(data, cell->GetId(1)),
                          d = point(data, cell->GetId(2));
    const Eigen::Vector3d face = (b - a).cross(d - a).normalized();
    for (vtkIdType j = 0; j < 3; ++j) {
      const Eigen::Vector3d n = tuple3(*normals, cell->GetId(j));
      largest = std::max(largest, std::atan2(n.cross(face).norm(), n.dot(face)));
    }
  }
  return largest;
}

// The solids file of a straight rod of 5 edges with `section` (12-gon
// ellipses, crease angle 60 degrees), read back.
vtkSmartPointer<vtkPolyData> straight_solid(const SectionSnapshot& section) {
  ScratchDirectory dir("straight_solid");
  const auto path = dir.path() / "solids.vtp";
  write_solids_file(straight_rod_snapshot(section, {0.2, -0.1, 0.4}, {1.1, 0.5, 0.1}, 5), path, {},
                    {12, 60.0});
  return read_polydata(path);
}

TEST_CASE("solids file: flat faces shade flat and smooth sections smoothly") {
  // Every corner of a rectangle is a crease: each face's corners carry its
  // own normal (8 ring points per node, 4 + 1 per cap).
  const auto flat = straight_solid({SectionSnapshot::Shape::Rectangle, 0.05, 0.02});
  CHECK(flat->GetNumberOfPoints() == 6 * 8 + 2 * 5);
  CHECK(flat->GetPoints()->GetDataType() == VTK_FLOAT);  // a picture: single precision
  CHECK(flat->GetPointData()->GetArray("Normals")->GetDataType() == VTK_FLOAT);
  // Single-precision points: a face normal from corners at coordinates of
  // order 1 that lie 0.02 apart is good to about 6e-8 / 0.02 = 3e-6 rad.
  const double resolution = 2e-5;
  CHECK(largest_normal_deviation(*flat) < resolution);
  // A 12-gon turns by 30 degrees at each corner, under the crease angle:
  // one point per corner with the mean of its two sides' normals, 15
  // degrees from each; the caps are flat.
  const int sides = 12;
  const auto smooth = straight_solid({SectionSnapshot::Shape::Ellipse, 0.04, 0.04});
  CHECK(smooth->GetNumberOfPoints() == 6 * sides + 2 * (sides + 1));
  CHECK(std::abs(largest_normal_deviation(*smooth) - kPi / sides) < resolution);
}

TEST_CASE("solids file: a section without width is rejected") {
  ScratchDirectory dir("bad_section");
  Snapshot snapshot = demo_snapshot();
  snapshot.rods[1].section.width = 0.0;
  CHECK_THROWS_AS(write_solids_file(snapshot, dir.path() / "solids.vtp"), std::invalid_argument);
  CHECK(file_names(dir.path()).empty());
}

}  // namespace xshell::test::solids_file_test
