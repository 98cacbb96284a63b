#include "render_test_support.hpp"

#include <doctest/doctest.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>

#include <algorithm>

namespace xshell::test {

RenderOptions sized(int width, int height, const std::string& color) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.color_array = color;
  return options;
}

std::set<unsigned> Pixels::colours() const {
  std::set<unsigned> packed;
  for (const Rgb& c : rgb)
    packed.insert((static_cast<unsigned>(c[0]) << 16) | (static_cast<unsigned>(c[1]) << 8) |
                  static_cast<unsigned>(c[2]));
  return packed;
}

double Pixels::drawn_fraction(int y0, int y1) const {
  long drawn = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < width; ++x) drawn += at(x, y) != Rgb{255, 255, 255};
  return y1 > y0 ? static_cast<double>(drawn) / (static_cast<double>(y1 - y0) * width) : 0.0;
}

double Pixels::differing_fraction(const Pixels& other) const {
  REQUIRE(other.rgb.size() == rgb.size());
  long differing = 0;
  for (size_t i = 0; i < rgb.size(); ++i) differing += rgb[i] != other.rgb[i];
  return rgb.empty() ? 0.0 : static_cast<double>(differing) / static_cast<double>(rgb.size());
}

bool saturated(const Rgb& c) {
  return *std::max_element(c.begin(), c.end()) - *std::min_element(c.begin(), c.end()) > 60;
}

Pixels read_pixels(const std::filesystem::path& path) {
  REQUIRE(std::filesystem::is_regular_file(path));
  vtkNew<vtkPNGReader> reader;
  REQUIRE(reader->CanReadFile(path.string().c_str()));
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  Pixels pixels;
  pixels.width = dims[0];
  pixels.height = dims[1];
  vtkDataArray* data = image->GetPointData()->GetScalars();
  REQUIRE(data);
  REQUIRE(data->GetNumberOfComponents() >= 3);
  for (vtkIdType i = 0; i < data->GetNumberOfTuples(); ++i) {
    const double* p = data->GetTuple(i);
    pixels.rgb.push_back({static_cast<int>(p[0]), static_cast<int>(p[1]), static_cast<int>(p[2])});
  }
  return pixels;
}

}  // namespace xshell::test
