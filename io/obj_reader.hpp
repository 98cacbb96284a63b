// Reader of linkage graphs from Wavefront OBJ line meshes.
//
// A linkage file holds vertices ("v x y z", an optional 4th w component is
// ignored) and rod segments ("l i j", or a polyline "l i j k ..." that becomes
// the edges i-j, j-k, ...). Indices are 1-based; a negative index counts back
// from the last vertex defined so far, as OBJ defines; "i/t" and "i/t/n"
// forms are accepted and only the vertex index is used. Comments (#), blank
// lines and the statements o, g, s, vt, vn, mtllib, usemtl are skipped. Lines
// end with LF, CRLF or CR alone.
//
// The reader accepts only a graph the model can be built from and otherwise
// throws one InputError whose message reads "FILE:LINE: what is wrong":
//   - syntax: unknown statements, faces (f), unparsable or non-finite
//     numbers, too few or too many coordinates, indices 0 or out of range;
//   - limits (input_file.hpp): a file larger than kMaxLinkageFileBytes,
//     more than kMaxLinkageSegments edges, a coordinate beyond
//     kMaxCoordinate, a linkage smaller than kMinLinkageSize across;
//   - edges: self-loops, duplicates (in either orientation), zero length;
//   - vertices: two at the same position (within 1e-12 of the bounding-box
//     diagonal), valence 0 (isolated) or above 4 (a scissor joint joins at
//     most four rod segments);
//   - the graph: no edges, more than one connected component.
// Topology errors point at the 'v' line of the offending vertex and give its
// 0-based index, the index every other input (configuration, outputs) uses.
#pragma once

#include <array>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "linkage/graph.hpp"

namespace xshell {

// A linkage graph with, for each vertex and edge, the 1-based line of the
// file that defined it (all edges of one polyline share its 'l' line), so
// that later checks can point the user at the file.
struct ObjLineGraph {
  LineGraph graph;
  std::vector<int> vertex_lines;  // size graph.vertices.size()
  std::vector<int> edge_lines;    // size graph.edges.size()
};

// Reads and checks the OBJ file at `path`; throws InputError when the file
// cannot be opened or is rejected (see above).
LineGraph read_obj(const std::string& path);
ObjLineGraph read_obj_with_lines(const std::string& path);

// Parses and checks OBJ text from `in` (or `text`); `name` stands for the
// file in messages, as they show it (see printable()).
LineGraph parse_obj(std::istream& in, const std::string& name);
ObjLineGraph parse_obj_with_lines(std::istream& in, const std::string& name);
ObjLineGraph parse_obj_text(std::string_view text, const std::string& name);

// A triangle mesh from an OBJ surface file ("v" and "f" lines; a polygon
// "f i j k l ..." becomes the triangles i-j-k, i-k-l, ...; indices as for
// linkages; 'l' lines are refused): the inverse design's target surface.
// Throws InputError "FILE:LINE: what is wrong" for syntax errors and
// indices out of range, and for a file without faces.
struct ObjSurface {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // 0-based vertex indices
};
ObjSurface read_obj_surface(const std::string& path);
ObjSurface parse_obj_surface_text(std::string_view text, const std::string& name);

}  // namespace xshell
