// How a .vtp file is encoded. Binary is VTK's appended raw section compressed
// with zlib at level 1, the fastest: small and fast, what ParaView reads best
// (on manta_ray's deployment, VTK's default level 5 made the files 1-7%
// smaller and the run's output 30% slower). ASCII is for reading a
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
