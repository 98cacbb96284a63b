#include "render_inputs.hpp"

#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataNormals.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <regex>
#include <system_error>

#include "io/input_error.hpp"

namespace xshell {
namespace fs = std::filesystem;

namespace {

// Silences VTK's error and warning display while it lives: a reader that
// fails says so on stderr in many lines, where xshell's one line (the
// InputError) is what the user should see.
class QuietVtk {
 public:
  QuietVtk() : previous_(vtkObject::GetGlobalWarningDisplay()) {
    vtkObject::GlobalWarningDisplayOff();
  }
  ~QuietVtk() { vtkObject::SetGlobalWarningDisplay(previous_); }
  QuietVtk(const QuietVtk&) = delete;
  QuietVtk& operator=(const QuietVtk&) = delete;

 private:
  int previous_;
};

DrawnAs drawn_as(vtkPolyData& data) {
  if (data.GetNumberOfPolys() > 0) return DrawnAs::Surface;
  if (data.GetNumberOfLines() > 0) return DrawnAs::Tubes;
  if (data.GetPointData()->GetArray("reaction_force") != nullptr) return DrawnAs::Arrows;
  return DrawnAs::Spheres;
}

// `surface` with point normals for its shape, split at sharp creases; its
// triangles are consistently outward already (solids_file.cpp).
vtkSmartPointer<vtkPolyData> with_normals(vtkPolyData* surface) {
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(surface);
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOff();
  normals->SplittingOn();
  normals->SetFeatureAngle(60.0);
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  normals->Update();
  return normals->GetOutput();
}

}  // namespace

RenderInput read_render_input(const std::string& path) {
  const std::string cannot = "render: cannot read '" + printable(path) + "'";
  std::error_code error;
  const auto status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(cannot + ": no such file");
  if (!fs::is_regular_file(status)) throw InputError(cannot + ": not a regular file");
  if (fs::file_size(path, error) == 0) throw InputError(cannot + ": the file is empty");
  const QuietVtk quiet;
  vtkNew<vtkXMLPolyDataReader> reader;
  if (!reader->CanReadFile(path.c_str()))
    throw InputError(cannot + ": not a VTK XML PolyData file (.vtp)");
  reader->SetFileName(path.c_str());
  reader->Update();
  if (reader->GetErrorCode() != 0 || reader->GetOutput() == nullptr ||
      reader->GetOutput()->GetNumberOfPoints() == 0)
    throw InputError(cannot + ": not a complete VTK PolyData file (truncated or malformed)");
  RenderInput input;
  input.path = path;
  input.data = vtkSmartPointer<vtkPolyData>::New();
  input.data->ShallowCopy(reader->GetOutput());
  input.drawn = drawn_as(*input.data);
  return input;
}

std::vector<RenderInput> drawn_inputs(std::vector<RenderInput> inputs) {
  bool surfaces = false;
  for (const RenderInput& input : inputs) surfaces = surfaces || input.drawn == DrawnAs::Surface;
  std::vector<RenderInput> drawn;
  for (RenderInput& input : inputs)
    if (!(surfaces && input.drawn == DrawnAs::Tubes)) drawn.push_back(std::move(input));
  if (drawn.empty()) throw InputError("render: no input has polygons, polylines or points to draw");
  return drawn;
}

std::string reference_file(const std::string& path) {
  static const std::regex kStep(R"(([a-z]+)_[0-9]{6}\.vtp)");
  const fs::path file(path);
  const std::string name = file.filename().string();
  std::smatch match;
  if (std::regex_match(name, match, kStep))
    return (file.parent_path() / (match[1].str() + "_000000.vtp")).string();
  if (name == "joint_forces.vtp") return (file.parent_path() / "joints_000000.vtp").string();
  return "";
}

void scale_deflection(std::vector<RenderInput>& inputs, double k) {
  for (RenderInput& input : inputs) {
    if (input.drawn == DrawnAs::Arrows) continue;
    const std::string reference = reference_file(input.path);
    const std::string cannot =
        "--scale-deflection: no reference geometry for '" + printable(input.path) + "'";
    std::error_code error;
    if (reference.empty() || !fs::is_regular_file(reference, error))
      throw InputError(cannot + (reference.empty()
                                     ? std::string(" (only a run's PART_NNNNNN.vtp and "
                                                   "joint_forces.vtp have one)")
                                     : " ('" + printable(reference) + "' is missing)"));
    const RenderInput start = read_render_input(reference);
    vtkPoints* from = start.data->GetPoints();
    const vtkIdType n = input.data->GetNumberOfPoints();
    if (from->GetNumberOfPoints() != n)
      throw InputError(cannot + ": '" + printable(reference) + "' has " +
                       std::to_string(from->GetNumberOfPoints()) + " points, it has " +
                       std::to_string(n));
    if (k == 1.0) continue;  // as written, to the last bit
    vtkNew<vtkPoints> moved;
    moved->SetDataTypeToDouble();
    moved->SetNumberOfPoints(n);
    for (vtkIdType p = 0; p < n; ++p) {
      double x[3], x0[3];
      input.data->GetPoint(p, x);
      from->GetPoint(p, x0);
      for (int i = 0; i < 3; ++i) x[i] = x0[i] + k * (x[i] - x0[i]);
      moved->SetPoint(p, x);
    }
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(input.data);
    copy->SetPoints(moved);
    copy->GetPointData()->RemoveArray("Normals");  // those of the solved shape
    input.data = input.drawn == DrawnAs::Surface ? with_normals(copy) : copy;
  }
}

}  // namespace xshell
