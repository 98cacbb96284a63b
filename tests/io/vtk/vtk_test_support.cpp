#include "vtk_test_support.hpp"

#include <doctest/doctest.h>
#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkXMLPolyDataReader.h>

#include <fstream>

namespace xshell::test {

vtkSmartPointer<vtkPolyData> read_polydata(const std::filesystem::path& path) {
  REQUIRE_MESSAGE(std::filesystem::is_regular_file(path), path.string());
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  REQUIRE_MESSAGE(reader->GetErrorCode() == vtkErrorCode::NoError, path.string());
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->ShallowCopy(reader->GetOutput());
  return data;
}

Eigen::Vector3d tuple3(vtkDataArray& array, vtkIdType i) {
  REQUIRE(array.GetNumberOfComponents() == 3);
  const double* v = array.GetTuple3(i);
  return {v[0], v[1], v[2]};
}

std::set<std::string> file_names(const std::filesystem::path& directory) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    if (entry.is_regular_file()) names.insert(entry.path().filename().string());
  return names;
}

std::string file_head(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

}  // namespace xshell::test
