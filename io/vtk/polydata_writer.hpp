// Internal to xshell::vtk (includes VTK headers; not for callers of the
// library): serializes a vtkPolyData with VTK's own vtkXMLPolyDataWriter and
// writes the bytes atomically (atomic_file.hpp).
#pragma once

#include <filesystem>

#include "write_options.hpp"

class vtkPolyData;

namespace xshell {

// data: the poly data to write; path: the target .vtp file. Throws
// OutputError naming `path` when VTK fails to serialize or the file cannot be
// written.
void write_polydata(vtkPolyData& data, const std::filesystem::path& path,
                    const WriteOptions& options);

}  // namespace xshell
