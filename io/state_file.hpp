// state.json: everything needed to restart a run exactly. Every segment's
// nodes, thetas, source frames and twist hints, every joint's parameters and
// reference frame, in the model's recentred coordinates with the origin that
// recentred them, and a fingerprint of the linkage (graph, subdivisions, rest
// shape, clamped free ends) so that a state from another linkage is refused.
//
// Layout:
// {
//   "format": "xshell-state", "version": 1,
//   "fingerprint": {"vertices": V, "edges": E, "subdivisions": n, "rest_shape": "input",
//                   "graph_hash": "16 hex digits", "clamped_ends": [v, ...]},
//   ("clamped_ends": the clamped free-end vertices, absent when there are none)
//   "origin": [x, y, z],
//   "segments": [{"nodes": [[x, y, z], ...], "thetas": [...],
//                 "source_frames": [{"tangent": [...], "d1": [...]}, ...], "twist_hints": [...]},
//                 ...],
//   "joints": [{"vertex": v, "params": [p(3), omega(3), alpha, l_A, l_B],
//               "reference_frame": [[b1], [b2], [n]]}, ...]
// }
#pragma once

#include <Eigen/Core>
#include <string>

#include "linkage/rod_linkage.hpp"

namespace xshell {

// Hex fingerprint of the linkage's graph (topology and coordinates).
std::string graph_hash(const LineGraph& graph);

// Writes the state atomically; throws OutputError.
void write_state(const std::string& path, const RodLinkage& linkage, const Eigen::Vector3d& origin);

// Reads a state written for `linkage` and restores it. Throws InputError when
// the file is unreadable or malformed, or belongs to another linkage.
void read_state(const std::string& path, RodLinkage& linkage, const Eigen::Vector3d& origin);

}  // namespace xshell
