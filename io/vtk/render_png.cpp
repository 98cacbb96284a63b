#include "render_png.hpp"

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "render_camera.hpp"
#include "render_error.hpp"
#include "render_scene.hpp"
#include "x_display.hpp"

namespace xshell {
namespace {

// The share of the picture's height under the drawing for the colour bar.
constexpr double kColorBarHeight = 0.16;

void check_options(const RenderOptions& options) {
  const auto side_ok = [](int pixels) { return pixels >= 1 && pixels <= kMaxPictureSide; };
  if (!side_ok(options.width) || !side_ok(options.height))
    throw InputError("render: the picture's width and height must be 1 to " +
                     std::to_string(kMaxPictureSide) + " pixels, got " +
                     std::to_string(options.width) + " x " + std::to_string(options.height));
  if (const auto& k = options.scale_deflection; k && !(std::isfinite(*k) && *k >= 0.0))
    throw InputError("--scale-deflection: must be a finite number >= 0, got " + std::to_string(*k));
}

// The window's pixels as PNG bytes.
vtkSmartPointer<vtkUnsignedCharArray> png_bytes(vtkRenderWindow& window) {
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(&window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(grab->GetOutputPort());
  png->WriteToMemoryOn();
  png->Write();
  return png->GetResult();
}

}  // namespace

void render_png(const std::vector<std::string>& vtp_files, const std::string& png_path,
                const RenderOptions& options) {
  check_options(options);
  // The inputs first: bad input is reported as such, display or not.
  std::vector<RenderInput> inputs;
  for (const std::string& path : vtp_files) inputs.push_back(read_render_input(path));
  inputs = drawn_inputs(std::move(inputs));
  if (options.scale_deflection) scale_deflection(inputs, *options.scale_deflection);
  const Coloring coloring = choose_coloring(inputs, options);
  const Scene scene = build_scene(inputs, coloring, options);

  const XDisplay display;
  vtkNew<vtkRenderWindow> window;
  if (window.GetPointer() == nullptr)  // no OpenGL factory registered (autoinit)
    throw RenderError("render: VTK has no render window implementation in this program");
  window->SetDisplayId(display.handle());
  window->SetOffScreenRendering(1);
  window->SetSize(options.width, options.height);

  const double bar = scene.color_bar ? kColorBarHeight : 0.0;
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1.0, 1.0, 1.0);
  renderer->SetViewport(0.0, bar, 1.0, 1.0);
  for (const auto& actor : scene.actors) renderer->AddActor(actor);
  std::vector<vtkPolyData*> shown;
  for (const auto& data : scene.geometry) shown.push_back(data);
  place_camera(*renderer->GetActiveCamera(), shown, options.view,
               options.width / (options.height * (1.0 - bar)));
  renderer->ResetCameraClippingRange();
  window->AddRenderer(renderer);
  vtkNew<vtkRenderer> legend;
  if (scene.color_bar) {
    legend->SetBackground(1.0, 1.0, 1.0);
    legend->SetViewport(0.0, 0.0, 1.0, bar);
    legend->AddActor2D(scene.color_bar);
    window->AddRenderer(legend);
  }
  window->Render();

  const auto bytes = png_bytes(*window);
  window->Finalize();  // release GL and X resources before the display closes
  if (bytes == nullptr || bytes->GetNumberOfValues() == 0)
    throw RenderError("render: VTK produced no PNG data for '" + printable(png_path) + "'");
  write_file_atomically(png_path,
                        std::string_view(reinterpret_cast<const char*>(bytes->GetPointer(0)),
                                         static_cast<size_t>(bytes->GetNumberOfValues())));
}

}  // namespace xshell
