// VTK polydata -> a TriangleMesh: every polygon split by vtkTriangleFilter
// (lines and points dropped and counted). The surface readers and the mesh
// surfaces (mesh_surfaces.h) share it; VTK types by name only.
#pragma once

#include <string>

#include "geometry/triangles/io/surface_reader.h"

class vtkPolyData;

namespace zs {

// `path` names the source in errors (a file, or what the surface was made of).
TriangleMesh triangles_of_polydata(vtkPolyData* pd, const std::string& path, SurfaceReadCounts* counts);

}  // namespace zs
