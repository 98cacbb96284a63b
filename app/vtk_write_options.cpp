#include "vtk_write_options.hpp"

namespace xshell {

namespace {

VtkCompression vtk_compression(OutputCompression compression) {
  switch (compression) {
    case OutputCompression::Zlib:
      return VtkCompression::Zlib;
    case OutputCompression::None:
      return VtkCompression::None;
    case OutputCompression::Lz4:
      break;
  }
  return VtkCompression::Lz4;
}

}  // namespace

WriteOptions vtk_write_options(const OutputOptions& output) {
  return {output.format == OutputFormat::Ascii ? VtkFormat::Ascii : VtkFormat::Binary,
          vtk_compression(output.compression)};
}

}  // namespace xshell
