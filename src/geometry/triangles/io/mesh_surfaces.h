// Surfaces made of a tet mesh, for the opaque geometry inside a volume
// (docs/scene.md, "Volumes with geometry"): the mesh's boundary (its
// topology's boundary faces, wound outward) and isosurfaces of its scalar
// (VTK's vtkContourFilter; cell data are averaged onto the points first, as
// vtkCellDataToPointData does, since a contour needs a field at the points).
#pragma once

#include <string>
#include <vector>

#include "geometry/tets/tet_mesh.h"
#include "geometry/triangles/triangle_mesh.h"

namespace zs {

// `name` names the mesh in errors. Throws FileError when nothing is left
// (no boundary face; no value crosses the scalar's range).
TriangleMesh boundary_surface(const TetMesh& m, const std::string& name);
TriangleMesh isosurfaces(const TetMesh& m, const std::vector<double>& values, const std::string& name);

}  // namespace zs
