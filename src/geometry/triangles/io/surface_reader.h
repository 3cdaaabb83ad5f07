// Triangle surfaces from files: .obj, .ply and .stl through VTK's readers,
// and OFF (the keyword OFF, COFF, NOFF, ... on its first line) through
// CGAL's. Polygons with more than three corners are split into triangles by
// VTK's vtkTriangleFilter (concave ones too); lines and points are dropped.
// Our classic tetrahedral .off starts with two counts, never the keyword, so
// the two formats never clash.
#pragma once

#include <string>

#include "geometry/triangles/surface_file.h"  // is_surface_file
#include "geometry/triangles/triangle_mesh.h"

namespace zs {

struct SurfaceReadCounts {
  size_t polygons = 0;       // faces in the file (any corner count)
  size_t split = 0;          // of those, with more than three corners
  size_t dropped = 0;        // lines, points and faces with fewer than three corners
};

// The surface's triangles (no normals yet). Throws FileError (one line naming
// the file) for a missing, unreadable or malformed file, or one with no
// triangle; an index out of range is an error, not a crash.
TriangleMesh read_surface(const std::string& path, SurfaceReadCounts* counts = nullptr);

}  // namespace zs
