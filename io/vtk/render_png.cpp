#include "render_png.hpp"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTubeFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "render_error.hpp"
#include "x_display.hpp"

namespace xshell {
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

vtkSmartPointer<vtkPolyData> read_vtp(const std::string& path) {
  const std::string cannot = "render: cannot read '" + printable(path) + "'";
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw InputError(cannot + ": no such file");
  if (!std::filesystem::is_regular_file(status)) throw InputError(cannot + ": not a regular file");
  if (std::filesystem::file_size(path, error) == 0)
    throw InputError(cannot + ": the file is empty");
  const QuietVtk quiet;
  vtkNew<vtkXMLPolyDataReader> reader;
  if (!reader->CanReadFile(path.c_str()))
    throw InputError(cannot + ": not a VTK XML PolyData file (.vtp)");
  reader->SetFileName(path.c_str());
  reader->Update();
  if (reader->GetErrorCode() != 0 || reader->GetOutput() == nullptr ||
      reader->GetOutput()->GetNumberOfPoints() == 0)
    throw InputError(cannot + ": not a complete VTK PolyData file (truncated or malformed)");
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->ShallowCopy(reader->GetOutput());
  return data;
}

// Where `name` lives on `data`: point data first, then cell data.
struct ColorSource {
  vtkDataArray* array = nullptr;
  bool on_points = true;
};
ColorSource find_array(vtkPolyData& data, const std::string& name) {
  if (vtkDataArray* a = data.GetPointData()->GetArray(name.c_str())) return {a, true};
  if (vtkDataArray* a = data.GetCellData()->GetArray(name.c_str())) return {a, false};
  return {};
}

double diagonal(const double bounds[6]) {
  return std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) +
                   std::pow(bounds[5] - bounds[4], 2));
}

// Polygon inputs if any, else polyline inputs turned into tubes.
std::vector<vtkSmartPointer<vtkPolyData>> drawable(
    const std::vector<vtkSmartPointer<vtkPolyData>>& inputs, const RenderOptions& options) {
  std::vector<vtkSmartPointer<vtkPolyData>> surfaces, lines;
  for (const auto& data : inputs) {
    if (data->GetNumberOfPolys() > 0)
      surfaces.push_back(data);
    else if (data->GetNumberOfLines() > 0)
      lines.push_back(data);
  }
  if (!surfaces.empty()) return surfaces;
  if (lines.empty()) throw InputError("render: no input has polygons or polylines to draw");

  double radius = options.tube_radius;
  if (!(radius > 0.0)) {
    double size = 0.0;
    for (const auto& data : lines) size = std::max(size, diagonal(data->GetBounds()));
    radius = (size > 0.0) ? 0.004 * size : 1e-3;
  }
  std::vector<vtkSmartPointer<vtkPolyData>> tubes;
  for (const auto& data : lines) {
    vtkNew<vtkTubeFilter> tube;
    tube->SetInputData(data);
    tube->SetRadius(radius);
    tube->SetNumberOfSides(12);
    tube->CappingOn();
    tube->Update();
    tubes.emplace_back(tube->GetOutput());
  }
  return tubes;
}

// Looks at the centre of the drawn bounding box from the direction
// (1, -1, 0.8), z up, from the nearest distance at which every drawn point
// fits the view with a 5% margin (vtkRenderer::ResetCamera fits the bounding
// sphere instead, which leaves a flat linkage small in the picture).
void fit_camera(vtkCamera& camera, const std::vector<vtkSmartPointer<vtkPolyData>>& shown,
                double aspect) {
  double lo[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                  std::numeric_limits<double>::max()};
  double hi[3] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
                  std::numeric_limits<double>::lowest()};
  for (const auto& data : shown) {
    const double* b = data->GetBounds();
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], b[2 * i]);
      hi[i] = std::max(hi[i], b[2 * i + 1]);
    }
  }
  const Eigen::Vector3d centre = 0.5 * (Eigen::Vector3d(lo) + Eigen::Vector3d(hi));
  const Eigen::Vector3d back = Eigen::Vector3d(1.0, -1.0, 0.8).normalized();  // to the eye
  const Eigen::Vector3d up = (Eigen::Vector3d::UnitZ() - back.z() * back).normalized();
  const Eigen::Vector3d right = up.cross(back);
  const double tan_half = std::tan(0.5 * camera.GetViewAngle() * 3.14159265358979323846 / 180.0);
  const double margin = 1.05;
  double distance = 0.0;
  for (const auto& data : shown)
    for (vtkIdType p = 0; p < data->GetNumberOfPoints(); ++p) {
      Eigen::Vector3d x;
      data->GetPoint(p, x.data());
      const Eigen::Vector3d r = x - centre;
      distance = std::max({distance, r.dot(back) + margin * std::abs(r.dot(up)) / tan_half,
                           r.dot(back) + margin * std::abs(r.dot(right)) / (tan_half * aspect)});
    }
  if (!(distance > 0.0)) distance = 1.0;  // a single point
  const Eigen::Vector3d eye = centre + distance * back;
  camera.SetFocalPoint(centre.data());
  camera.SetPosition(eye.data());
  camera.SetViewUp(up.data());
}

}  // namespace

void render_png(const std::vector<std::string>& vtp_files, const std::string& png_path,
                const RenderOptions& options) {
  const auto side_ok = [](int pixels) { return pixels >= 1 && pixels <= kMaxPictureSide; };
  if (!side_ok(options.width) || !side_ok(options.height))
    throw InputError("render: the picture's width and height must be 1 to " +
                     std::to_string(kMaxPictureSide) + " pixels, got " +
                     std::to_string(options.width) + " x " + std::to_string(options.height));
  // The inputs first: bad input is reported as such, display or not.
  std::vector<vtkSmartPointer<vtkPolyData>> inputs;
  for (const std::string& path : vtp_files) inputs.push_back(read_vtp(path));
  const std::vector<vtkSmartPointer<vtkPolyData>> shown = drawable(inputs, options);

  // The colour array's range over every drawn input.
  double range[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()};
  bool colored = false;
  for (const auto& data : shown) {
    if (options.color_array.empty()) break;
    if (ColorSource source = find_array(*data, options.color_array); source.array != nullptr) {
      double r[2];
      source.array->GetRange(r, source.array->GetNumberOfComponents() > 1 ? -1 : 0);
      range[0] = std::min(range[0], r[0]);
      range[1] = std::max(range[1], r[1]);
      colored = true;
    }
  }
  if (!options.color_array.empty() && !colored)
    throw InputError("render: no drawn input has an array named '" +
                     printable(options.color_array) + "' to colour by");
  if (colored && !(range[1] > range[0])) range[1] = range[0] + 1.0;  // constant field

  const XDisplay display;

  vtkNew<vtkLookupTable> table;
  table->SetHueRange(0.667, 0.0);  // blue (low) to red (high)
  if (colored) table->SetTableRange(range);
  table->Build();

  vtkNew<vtkRenderWindow> window;
  if (window.GetPointer() == nullptr)  // no OpenGL factory registered (autoinit)
    throw RenderError("render: VTK has no render window implementation in this program");
  window->SetDisplayId(display.handle());
  window->SetOffScreenRendering(1);
  window->SetSize(options.width, options.height);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  for (const auto& data : shown) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(data);
    const ColorSource source = colored ? find_array(*data, options.color_array) : ColorSource{};
    if (source.array != nullptr) {
      mapper->ScalarVisibilityOn();
      if (source.on_points)
        mapper->SetScalarModeToUsePointFieldData();
      else
        mapper->SetScalarModeToUseCellFieldData();
      mapper->SelectColorArray(options.color_array.c_str());
      mapper->SetLookupTable(table);
      mapper->UseLookupTableScalarRangeOn();
    } else {
      mapper->ScalarVisibilityOff();
    }
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    if (source.array == nullptr) actor->GetProperty()->SetColor(0.55, 0.6, 0.7);
    renderer->AddActor(actor);
  }

  fit_camera(*renderer->GetActiveCamera(), shown,
             static_cast<double>(options.width) / options.height);
  renderer->ResetCameraClippingRange();

  window->AddRenderer(renderer);
  window->Render();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();

  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(grab->GetOutputPort());
  png->WriteToMemoryOn();
  png->Write();
  vtkUnsignedCharArray* bytes = png->GetResult();
  window->Finalize();  // release GL and X resources before the display closes
  if (bytes == nullptr || bytes->GetNumberOfValues() == 0)
    throw RenderError("render: VTK produced no PNG data for '" + printable(png_path) + "'");
  write_file_atomically(png_path,
                        std::string_view(reinterpret_cast<const char*>(bytes->GetPointer(0)),
                                         static_cast<size_t>(bytes->GetNumberOfValues())));
}

}  // namespace xshell
