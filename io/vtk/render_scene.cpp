#include "render_scene.hpp"

#include <vtkArrowSource.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkGlyph3D.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>
#include <vtkTubeFilter.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "io/input_error.hpp"
#include "io/unit_names.hpp"
#include "vtk_arrays.hpp"

namespace xshell {
namespace {

// The colour bar's font when installed (Debian: fonts-dejavu-core): VTK's
// own font draws "[" and "]" as "(" and ")".
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

vtkDataArray* find_array(vtkPolyData& data, const std::string& name, bool* on_points = nullptr) {
  if (vtkDataArray* a = data.GetPointData()->GetArray(name.c_str())) {
    if (on_points) *on_points = true;
    return a;
  }
  if (on_points) *on_points = false;
  return data.GetCellData()->GetArray(name.c_str());
}

std::string available_arrays(const std::vector<RenderInput>& inputs) {
  std::set<std::string> names;
  for (const RenderInput& input : inputs)
    for (vtkFieldData* fields : {static_cast<vtkFieldData*>(input.data->GetPointData()),
                                 static_cast<vtkFieldData*>(input.data->GetCellData())})
      for (int i = 0; i < fields->GetNumberOfArrays(); ++i)
        if (const char* name = fields->GetArrayName(i); name && fields->GetArray(i))
          names.insert(name);
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "none" : list;
}

double diagonal(const std::vector<RenderInput>& inputs) {
  double lo[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                  std::numeric_limits<double>::max()};
  double hi[3] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
                  std::numeric_limits<double>::lowest()};
  for (const RenderInput& input : inputs) {
    const double* b = input.data->GetBounds();
    for (int i = 0; i < 3; ++i)
      lo[i] = std::min(lo[i], b[2 * i]), hi[i] = std::max(hi[i], b[2 * i + 1]);
  }
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += (hi[i] - lo[i]) * (hi[i] - lo[i]);
  return std::sqrt(sum);
}

vtkSmartPointer<vtkPolyData> tubes(vtkPolyData* lines, double radius) {
  vtkNew<vtkTubeFilter> tube;
  tube->SetInputData(lines);
  tube->SetRadius(radius);
  tube->SetNumberOfSides(12);
  tube->CappingOn();
  tube->Update();
  return tube->GetOutput();
}

vtkSmartPointer<vtkPolyData> spheres(vtkPolyData* points, double radius) {
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(12);
  vtkNew<vtkGlyph3D> glyph;
  glyph->SetInputData(points);
  glyph->SetSourceConnection(sphere->GetOutputPort());
  glyph->ScalingOff();
  glyph->OrientOff();
  glyph->Update();
  return glyph->GetOutput();
}

// Arrows from each point along its reaction_force, the largest `longest`
// long; empty when every force is zero.
vtkSmartPointer<vtkPolyData> arrows(vtkPolyData* points, double longest) {
  vtkDataArray* force = points->GetPointData()->GetArray("reaction_force");
  const double largest = force->GetMaxNorm();
  vtkNew<vtkArrowSource> arrow;
  arrow->SetTipResolution(16);
  arrow->SetShaftResolution(16);
  vtkNew<vtkGlyph3D> glyph;
  glyph->SetInputData(points);
  glyph->SetSourceConnection(arrow->GetOutputPort());
  glyph->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "reaction_force");
  glyph->SetVectorModeToUseVector();
  glyph->SetScaleModeToScaleByVector();
  glyph->SetScaleFactor(largest > 0.0 ? longest / largest : 0.0);
  glyph->OrientOn();
  glyph->Update();
  return glyph->GetOutput();
}

}  // namespace

Coloring choose_coloring(const std::vector<RenderInput>& inputs, const RenderOptions& options) {
  Coloring c;
  if (options.color_array.empty()) return c;
  c.range[0] = std::numeric_limits<double>::max();
  c.range[1] = std::numeric_limits<double>::lowest();
  for (const RenderInput& input : inputs) {
    vtkDataArray* a = find_array(*input.data, options.color_array);
    if (a == nullptr) continue;
    double r[2];
    a->GetRange(r, a->GetNumberOfComponents() > 1 ? -1 : 0);
    c.range[0] = std::min(c.range[0], r[0]);
    c.range[1] = std::max(c.range[1], r[1]);
    if (c.array.empty()) {
      c.array = options.color_array;
      const std::string unit = array_unit(*input.data, c.array);
      const auto folder = std::filesystem::path(input.path).parent_path();
      c.title =
          unit.empty() ? c.array : c.array + " [" + unit_label(unit, run_unit_names(folder)) + "]";
    }
  }
  if (c.array.empty() && !options.color_optional)
    throw InputError("render: no drawn input has an array named '" +
                     printable(options.color_array) +
                     "' to colour by; the arrays are: " + available_arrays(inputs));
  if (!c.array.empty() && !(c.range[1] > c.range[0])) c.range[1] = c.range[0] + 1.0;  // constant
  return c;
}

Scene build_scene(const std::vector<RenderInput>& inputs, const Coloring& coloring,
                  const RenderOptions& options) {
  const double size = diagonal(inputs);
  const double scale = size > 0.0 ? size : 1.0;
  const double radius = options.tube_radius > 0.0 ? options.tube_radius : 0.004 * scale;
  Scene scene;
  vtkNew<vtkLookupTable> table;
  table->SetHueRange(0.667, 0.0);  // blue (low) to red (high)
  table->SetTableRange(coloring.range);
  table->Build();
  for (const RenderInput& input : inputs) {
    vtkSmartPointer<vtkPolyData> shape = input.data;
    if (input.drawn == DrawnAs::Tubes) shape = tubes(input.data, radius);
    if (input.drawn == DrawnAs::Spheres) shape = spheres(input.data, 3.0 * radius);
    if (input.drawn == DrawnAs::Arrows) shape = arrows(input.data, 0.15 * scale);
    scene.geometry.push_back(shape);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(shape);
    bool on_points = true;
    const bool colored =
        !coloring.array.empty() && find_array(*shape, coloring.array, &on_points) != nullptr;
    mapper->SetScalarVisibility(colored);
    if (colored) {
      if (on_points)
        mapper->SetScalarModeToUsePointFieldData();
      else
        mapper->SetScalarModeToUseCellFieldData();
      mapper->SelectColorArray(coloring.array.c_str());
      mapper->SetLookupTable(table);
      mapper->UseLookupTableScalarRangeOn();
    }
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    // Some ambient light: a face seen at grazing incidence (a lath seen
    // end-on from the front) keeps its colour instead of turning black.
    actor->GetProperty()->SetAmbient(0.35);
    actor->GetProperty()->SetDiffuse(0.65);
    if (!colored && input.drawn == DrawnAs::Arrows)
      actor->GetProperty()->SetColor(0.8, 0.1, 0.1);
    else if (!colored && input.drawn == DrawnAs::Spheres)
      actor->GetProperty()->SetColor(0.25, 0.25, 0.3);
    else if (!colored)
      actor->GetProperty()->SetColor(0.55, 0.6, 0.7);
    scene.actors.push_back(actor);
  }
  if (coloring.array.empty()) return scene;
  scene.color_bar = vtkSmartPointer<vtkScalarBarActor>::New();
  vtkScalarBarActor& bar = *scene.color_bar;
  bar.SetLookupTable(table);
  bar.SetTitle(coloring.title.c_str());
  bar.SetOrientationToHorizontal();
  bar.SetNumberOfLabels(5);
  bar.SetLabelFormat("%.3g");
  bar.SetPosition(0.1, 0.05);
  bar.SetWidth(0.8);
  bar.SetHeight(0.9);
  std::error_code no_font;
  const bool dejavu = std::filesystem::is_regular_file(kFont, no_font);
  for (vtkTextProperty* text : {bar.GetTitleTextProperty(), bar.GetLabelTextProperty()}) {
    if (dejavu) {
      text->SetFontFamily(VTK_FONT_FILE);
      text->SetFontFile(kFont);
    }
    text->SetColor(0.0, 0.0, 0.0);
    text->ShadowOff();
    text->ItalicOff();
    text->BoldOff();
  }
  return scene;
}

}  // namespace xshell
