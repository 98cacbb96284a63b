// Helpers of the VTK writer tests: reading a .vtp back, reading tuples (and
// the scratch directory they write in).
#pragma once

#include <doctest/doctest.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <filesystem>
#include <set>
#include <string>

#include "scratch_directory.hpp"

// CHECK(expr) and count it, so that a test can assert at its end how many
// checks ran and cannot pass by checking nothing.
#define XSHELL_COUNTED_CHECK(counter, ...) \
  do {                                     \
    CHECK(__VA_ARGS__);                    \
    ++(counter);                           \
  } while (false)

namespace xshell::test {

// Reads `path` with vtkXMLPolyDataReader; fails the current test case
// (REQUIRE) when the file cannot be read.
vtkSmartPointer<vtkPolyData> read_polydata(const std::filesystem::path& path);

// Tuple `i` of a 3-component array.
Eigen::Vector3d tuple3(vtkDataArray& array, vtkIdType i);

// The names of the regular files in `directory`.
std::set<std::string> file_names(const std::filesystem::path& directory);

// The first 4096 bytes of a file (to look at an XML header).
std::string file_head(const std::filesystem::path& path);

}  // namespace xshell::test
