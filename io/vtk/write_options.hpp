// How a .vtp file is encoded. Binary is VTK's appended raw section,
// compressed by default with LZ4, VTK's fastest compressor: a plain
// relaxation of manta_ray writing every iteration took 0.27 s with it and
// 0.33 s with zlib at level 1 (the output phase 0.037 against 0.090 s,
// the files 6.5 MB against 4.6 MB; uncompressed, as fast and 15.9 MB).
// ParaView reads all three (LZ4 since VTK 8.1 and ParaView 5.5); zlib is
// for older readers. ASCII is for reading a file by eye or diffing it.
#pragma once

namespace xshell {

enum class VtkFormat {
  Binary,  // appended data, compressed (default)
  Ascii,   // inline text
};

enum class VtkCompression {
  Lz4,   // vtkLZ4DataCompressor at its best ratio, level 9 (default)
  Zlib,  // vtkZLibDataCompressor at level 1, its fastest
  None,  // raw bytes
};

struct WriteOptions {
  VtkFormat format = VtkFormat::Binary;
  VtkCompression compression = VtkCompression::Lz4;  // binary only
};

}  // namespace xshell
