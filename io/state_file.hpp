// state.json: everything needed to restart a run exactly. Every segment's
// nodes, thetas, source frames and twist hints, every joint's parameters and
// reference frame, in the model's recentred coordinates with the origin that
// recentred them, and a fingerprint of the linkage (graph, subdivisions, rest
// shape, clamped free ends, rest lengths given) so that a state from another
// linkage is refused.
//
// Layout:
// {
//   "format": "xshell-state", "version": 1,
//   "fingerprint": {"vertices": V, "edges": E, "subdivisions": n, "rest_shape": "input",
//                   "graph_hash": "16 hex digits", "clamped_ends": [v, ...],
//                   "rest_lengths": [L, ...]},
//   ("clamped_ends": the clamped free-end vertices, absent when there are none;
//    "rest_lengths": the segments' rest lengths of the configuration's "rest_lengths",
//    absent when it gives none, so older states of such runs still match)
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

// The text of state.json (the layout above).
std::string state_text(const RodLinkage& linkage, const Eigen::Vector3d& origin);

// Writes the state atomically; throws OutputError.
void write_state(const std::string& path, const RodLinkage& linkage, const Eigen::Vector3d& origin);

// Reads a state written for `linkage` and restores it. `origin` is this
// run's (the input's bounding-box centre). Throws InputError when the file
// cannot be read (see read_input_file: a regular file of at most
// kMaxStateFileBytes), is no JSON or no state, belongs to another linkage,
// or holds a value that xshell would not have written: a number that is not
// finite, a coordinate beyond kMaxCoordinate, an origin other than this
// run's, a segment edge of zero length, a source frame or a joint's
// reference frame that is not orthonormal (to 1e-6), a joint of another
// vertex, or a state whose elastic energy is not finite.
void read_state(const std::string& path, RodLinkage& linkage, const Eigen::Vector3d& origin);

// The same from the file's `text`; `name` stands for the file in messages,
// as they show it (see printable()).
void restore_state(const std::string& text, const std::string& name, RodLinkage& linkage,
                   const Eigen::Vector3d& origin);

}  // namespace xshell
