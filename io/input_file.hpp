// What xshell reads from a user, and how much of it. Every input file (the
// configuration, the linkage, an --init state) is read whole by
// read_input_file, which accepts only a regular file: a FIFO would block the
// run, a device such as /dev/zero would be read forever, a folder is no
// file. Each kind of file has a size limit, checked before reading and
// while reading (a file may grow). These limits and the others below are the
// README's "Limits".
#pragma once

#include <cstdint>
#include <string>

#include "linkage/rod_linkage.hpp"

namespace xshell {

// Most rod edges (graph edges x subdivisions) a run may have: far above the
// largest benchmark grid (1e5 unknowns) and any published design.
constexpr long kMaxRodEdges = 2000000;

// Most segments (graph edges) a linkage file may have: kMaxRodEdges at the
// fewest subdivisions the model allows.
constexpr long kMaxLinkageSegments = kMaxRodEdges / kMinSubdivisions;

// Coordinates of a linkage file: |x|, |y|, |z| at most kMaxCoordinate, and
// the linkage (its bounding-box diagonal) at least kMinLinkageSize across, in
// the file's length unit (millimetres and metres are both far inside). Past
// these, squared lengths overflow or underflow and the model's and the
// outputs' tolerances no longer mean anything.
constexpr double kMaxCoordinate = 1e12;
constexpr double kMinLinkageSize = 1e-6;

// Largest file of each kind, in bytes. A linkage of kMaxLinkageSegments
// segments takes about 60 MB (70 bytes per vertex, 20 per segment); a
// configuration of 1.5 million point forces 61 MB; a state about 290 bytes
// per rod edge, 0.6 GB at kMaxRodEdges.
constexpr std::uintmax_t kMaxLinkageFileBytes = 256u << 20;        // 256 MiB
constexpr std::uintmax_t kMaxConfigurationFileBytes = 256u << 20;  // 256 MiB
constexpr std::uintmax_t kMaxStateFileBytes = 1024u << 20;         // 1 GiB

// A kind of input file: its name in messages ("configuration file") and its
// size limit.
struct InputFileKind {
  const char* name;
  std::uintmax_t max_bytes;
};
constexpr InputFileKind kLinkageFile{"linkage file", kMaxLinkageFileBytes};
constexpr InputFileKind kConfigurationFile{"configuration file", kMaxConfigurationFileBytes};
constexpr InputFileKind kStateFile{"state file", kMaxStateFileBytes};
constexpr InputFileKind kSurfaceFile{"surface file", kMaxLinkageFileBytes};

// The whole content of the regular file at `path`. Throws InputError
// "<failure>: <reason>" when it cannot be read: it does not exist or may not
// be read (the system's reason), it is a folder, a FIFO, a device or a
// socket, or it is larger than kind.max_bytes. `failure` says what failed
// in the caller's words ("cannot open linkage file 'grid.obj'").
std::string read_input_file(const std::string& path, const InputFileKind& kind,
                            const std::string& failure);

}  // namespace xshell
