// wireframe.ply (SPEC section 3): an ASCII PLY file with `element vertex` (x y z, double) and
// `element edge` (vertex1 vertex2, int), the shape Open3D's read_line_set, MeshLab and
// CloudCompare open. The format: Turk, "The PLY Polygon File Format", 1994.
#pragma once

#include <string>

#include "backend/export/wireframe.h"
#include "util/status.h"

namespace sfm {

// The PLY text of a wireframe. The header is exactly
//   ply / format ascii 1.0 / element vertex N / property double x / property double y /
//   property double z / [property int track_id /] element edge M / property int vertex1 /
//   property int vertex2 / end_header
// (one item per line; track_id when wireframe.track_ids is not empty), then one "x y z [track_id]"
// line per vertex (metres, shortest round-trip numbers) and one "vertex1 vertex2" line per edge.
// Fails on a non-finite vertex coordinate, an edge index outside [0, N) or a track_ids of another
// size than the vertices, naming the vertex or edge.
Status FormatPly(const ReconstructedWireframe& wireframe, std::string* text);

// FormatPly written atomically to `path` (util/atomic_file.h); errors are prefixed by the path.
Status WritePly(const std::string& path, const ReconstructedWireframe& wireframe);

// Reads an ASCII PLY file holding `element vertex` with scalar properties x, y, z, optionally
// track_id (others are ignored) and optionally `element edge` with vertex1, vertex2; other elements are
// skipped. Enough for our own files and the tests; binary PLY is reported as unsupported. Fails, naming the
// file and line, on a malformed header or data line and on an edge index outside the vertices.
Status ReadPly(const std::string& path, ReconstructedWireframe* wireframe);

}  // namespace sfm
