// How a .vtp file is encoded. Binary is VTK's appended raw section compressed
// with zlib: small and fast, what ParaView reads best. ASCII is for reading a
// file by eye or diffing it.
#pragma once

namespace xshell {

enum class VtkFormat {
  Binary,  // appended data, zlib-compressed (default)
  Ascii,   // inline text
};

struct WriteOptions {
  VtkFormat format = VtkFormat::Binary;
};

}  // namespace xshell
