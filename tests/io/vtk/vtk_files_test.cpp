// Writes the rods, frames and joints files of the demo snapshot in every
// encoding (binary with each compressor, ASCII) and reads them back with
// VTK's own reader.
#include <doctest/doctest.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdList.h>
#include <vtkPointData.h>

#include <cmath>

#include "demo_snapshot.hpp"
#include "io/vtk/frames_file.hpp"
#include "io/vtk/joints_file.hpp"
#include "io/vtk/rods_file.hpp"
#include "vtk_test_support.hpp"

namespace xshell::test {
namespace {

constexpr double kTol = 1e-12;

struct Format {
  WriteOptions options;
  const char* name;
  const char* compressor;  // the header's compressor attribute, "" for none
};
const Format kFormats[] = {
    {{VtkFormat::Binary, VtkCompression::Lz4}, "lz4", "vtkLZ4DataCompressor"},
    {{VtkFormat::Binary, VtkCompression::Zlib}, "zlib", "vtkZLibDataCompressor"},
    {{VtkFormat::Binary, VtkCompression::None}, "raw", ""},
    {{VtkFormat::Ascii}, "ascii", ""}};

// The header's compressor attribute, "" without one.
std::string compressor_of(const std::string& head) {
  const std::string key = "compressor=\"";
  const size_t start = head.find(key);
  if (start == std::string::npos) return "";
  const size_t begin = start + key.size();
  return head.substr(begin, head.find('"', begin) - begin);
}

// The encoding the header announces: appended data and its compressor, or
// inline ASCII.
void check_encoding(const std::filesystem::path& path, const Format& format, int& checks) {
  const std::string head = file_head(path);
  XSHELL_COUNTED_CHECK(checks, compressor_of(head) == format.compressor);
  const bool binary = format.options.format == VtkFormat::Binary;
  XSHELL_COUNTED_CHECK(
      checks, head.find(binary ? "format=\"appended\"" : "format=\"ascii\"") != std::string::npos);
}

}  // namespace

TEST_CASE("rods file: one polyline per rod with per-node data") {
  const Snapshot snapshot = demo_snapshot(1.5);
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    ScratchDirectory dir("rods");
    const auto path = dir.path() / "rods.vtp";
    write_rods_file(snapshot, path, format.options);
    int checks = 0;
    check_encoding(path, format, checks);

    const auto data = read_polydata(path);
    REQUIRE(data->GetNumberOfPoints() == 9 + 7);
    REQUIRE(data->GetNumberOfLines() == 2);
    REQUIRE(data->GetNumberOfCells() == 2);
    vtkDataArray* rod_id = data->GetCellData()->GetArray("rod_id");
    vtkPointData* pd = data->GetPointData();
    vtkDataArray* segment = pd->GetArray("segment_id");
    vtkDataArray* curvature = pd->GetArray("curvature");
    vtkDataArray* twist = pd->GetArray("twist");
    vtkDataArray* bending = pd->GetArray("bending_density");
    vtkDataArray* twisting = pd->GetArray("twisting_density");
    REQUIRE(rod_id);
    REQUIRE(segment);
    REQUIRE(curvature);
    REQUIRE(twist);
    REQUIRE(bending);
    REQUIRE(twisting);

    vtkNew<vtkIdList> cell;
    vtkIdType cell_id = 0;
    for (const RodSnapshot& rod : snapshot.rods) {
      XSHELL_COUNTED_CHECK(checks, rod_id->GetTuple1(cell_id) == rod.rod_id);
      data->GetCellPoints(cell_id, cell);
      REQUIRE(cell->GetNumberOfIds() == static_cast<vtkIdType>(rod.nodes.size()));
      for (size_t k = 0; k < rod.nodes.size(); ++k) {
        const vtkIdType p = cell->GetId(static_cast<vtkIdType>(k));
        Eigen::Vector3d x;
        data->GetPoint(p, x.data());
        XSHELL_COUNTED_CHECK(checks, (x - rod.nodes[k]).norm() < kTol);
        XSHELL_COUNTED_CHECK(checks, segment->GetTuple1(p) == rod.edge_segment[k == 0 ? 0 : k - 1]);
        XSHELL_COUNTED_CHECK(checks, std::abs(curvature->GetTuple1(p) - rod.curvature[k]) < kTol);
        XSHELL_COUNTED_CHECK(checks, std::abs(twist->GetTuple1(p) - rod.twist[k]) < kTol);
        XSHELL_COUNTED_CHECK(checks,
                             std::abs(bending->GetTuple1(p) - rod.bending_density[k]) < kTol);
        XSHELL_COUNTED_CHECK(checks,
                             std::abs(twisting->GetTuple1(p) - rod.twisting_density[k]) < kTol);
      }
      ++cell_id;
    }
    // 2 encoding checks, 1 per rod, 6 per node.
    CHECK(checks == 2 + 2 + 6 * (9 + 7));
  }
}

TEST_CASE("frames file: unit orthogonal material frames at edge midpoints") {
  const Snapshot snapshot = demo_snapshot(0.25);
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    ScratchDirectory dir("frames");
    const auto path = dir.path() / "frames.vtp";
    write_frames_file(snapshot, path, format.options);
    int checks = 0;
    check_encoding(path, format, checks);

    const auto data = read_polydata(path);
    REQUIRE(data->GetNumberOfPoints() == 8 + 6);
    REQUIRE(data->GetNumberOfVerts() == 8 + 6);
    REQUIRE(data->GetNumberOfCells() == 8 + 6);
    vtkPointData* pd = data->GetPointData();
    vtkDataArray* d1 = pd->GetArray("d1");
    vtkDataArray* d2 = pd->GetArray("d2");
    vtkDataArray* rod_id = pd->GetArray("rod_id");
    vtkDataArray* segment = pd->GetArray("segment_id");
    vtkDataArray* stretching = pd->GetArray("stretching_density");
    vtkDataArray* length = pd->GetArray("edge_length");
    REQUIRE(d1);
    REQUIRE(d2);
    REQUIRE(rod_id);
    REQUIRE(segment);
    REQUIRE(stretching);
    REQUIRE(length);
    REQUIRE(d1->GetNumberOfComponents() == 3);
    REQUIRE(d2->GetNumberOfComponents() == 3);

    vtkIdType p = 0;
    for (const RodSnapshot& rod : snapshot.rods) {
      for (size_t i = 0; i + 1 < rod.nodes.size(); ++i, ++p) {
        const Eigen::Vector3d edge = rod.nodes[i + 1] - rod.nodes[i];
        const Eigen::Vector3d t = edge.normalized();
        const Eigen::Vector3d a = tuple3(*d1, p), b = tuple3(*d2, p);
        Eigen::Vector3d x;
        data->GetPoint(p, x.data());
        XSHELL_COUNTED_CHECK(checks, (x - 0.5 * (rod.nodes[i] + rod.nodes[i + 1])).norm() < kTol);
        XSHELL_COUNTED_CHECK(checks, std::abs(a.norm() - 1.0) < kTol);
        XSHELL_COUNTED_CHECK(checks, std::abs(b.norm() - 1.0) < kTol);
        XSHELL_COUNTED_CHECK(checks, std::abs(a.dot(b)) < kTol);
        XSHELL_COUNTED_CHECK(checks, std::abs(a.dot(t)) < kTol);
        XSHELL_COUNTED_CHECK(checks, std::abs(b.dot(t)) < kTol);
        XSHELL_COUNTED_CHECK(checks, (a - rod.d1[i]).norm() < kTol);
        XSHELL_COUNTED_CHECK(checks, (b - rod.d2[i]).norm() < kTol);
        XSHELL_COUNTED_CHECK(checks, rod_id->GetTuple1(p) == rod.rod_id);
        XSHELL_COUNTED_CHECK(checks, segment->GetTuple1(p) == rod.edge_segment[i]);
        XSHELL_COUNTED_CHECK(checks,
                             std::abs(stretching->GetTuple1(p) - rod.stretching_density[i]) < kTol);
        XSHELL_COUNTED_CHECK(checks, std::abs(length->GetTuple1(p) - edge.norm()) < kTol);
      }
    }
    CHECK(checks == 2 + 12 * (8 + 6));
  }
}

TEST_CASE("joints file: one vertex per joint with the snapshot's normals") {
  const Snapshot snapshot = demo_snapshot(0.0);
  REQUIRE(snapshot.joints.size() == 5);
  for (const Format& format : kFormats) {
    CAPTURE(format.name);
    ScratchDirectory dir("joints");
    const auto path = dir.path() / "joints.vtp";
    write_joints_file(snapshot, path, format.options);
    int checks = 0;
    check_encoding(path, format, checks);

    const auto data = read_polydata(path);
    REQUIRE(data->GetNumberOfPoints() == 5);
    REQUIRE(data->GetNumberOfVerts() == 5);
    vtkPointData* pd = data->GetPointData();
    vtkDataArray* vertex = pd->GetArray("vertex");
    vtkDataArray* normal = pd->GetArray("normal");
    vtkDataArray* angle = pd->GetArray("opening_angle");
    vtkDataArray* valence = pd->GetArray("valence");
    REQUIRE(vertex);
    REQUIRE(normal);
    REQUIRE(angle);
    REQUIRE(valence);
    for (vtkIdType p = 0; p < 5; ++p) {
      const JointSnapshot& joint = snapshot.joints[static_cast<size_t>(p)];
      Eigen::Vector3d x;
      data->GetPoint(p, x.data());
      XSHELL_COUNTED_CHECK(checks, (x - joint.position).norm() < kTol);
      XSHELL_COUNTED_CHECK(checks, vertex->GetTuple1(p) == joint.vertex);
      XSHELL_COUNTED_CHECK(checks, (tuple3(*normal, p) - joint.normal).norm() < kTol);
      XSHELL_COUNTED_CHECK(checks, std::abs(angle->GetTuple1(p) - joint.opening_angle) < kTol);
      XSHELL_COUNTED_CHECK(checks, valence->GetTuple1(p) == joint.valence);
    }
    CHECK(checks == 2 + 5 * 5);
  }
}

TEST_CASE("an empty snapshot gives valid empty files") {
  ScratchDirectory dir("empty");
  const Snapshot empty;
  write_rods_file(empty, dir.path() / "rods.vtp");
  write_frames_file(empty, dir.path() / "frames.vtp");
  write_joints_file(empty, dir.path() / "joints.vtp");
  int checks = 0;
  for (const char* name : {"rods.vtp", "frames.vtp", "joints.vtp"}) {
    CAPTURE(name);
    XSHELL_COUNTED_CHECK(checks, read_polydata(dir.path() / name)->GetNumberOfPoints() == 0);
  }
  CHECK(checks == 3);
}

TEST_CASE("an inconsistent snapshot is rejected before anything is written") {
  ScratchDirectory dir("invalid");
  Snapshot snapshot = demo_snapshot();
  snapshot.rods[1].d2.pop_back();
  CHECK_THROWS_AS(write_rods_file(snapshot, dir.path() / "rods.vtp"), std::invalid_argument);
  CHECK_THROWS_AS(write_frames_file(snapshot, dir.path() / "frames.vtp"), std::invalid_argument);
  CHECK(file_names(dir.path()).empty());
}

}  // namespace xshell::test
