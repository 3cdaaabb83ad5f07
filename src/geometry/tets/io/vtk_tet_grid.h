// A tet mesh as VTK's unstructured grid (double points, one VTK_TETRA per
// tet, the scalar as point or cell data named as the mesh names it): what
// the .vtu writer writes and VTK's filters take (mesh surfaces). VTK types by
// name only, for the VTK-backed code beside it.
#pragma once

#include <string>

#include <vtkSmartPointer.h>

#include "geometry/tets/tet_mesh.h"

class vtkUnstructuredGrid;

namespace zs {

// Throws FileError naming `path` for a tet index out of range or scalars
// whose count does not fit the mesh.
vtkSmartPointer<vtkUnstructuredGrid> vtk_tet_grid(const TetMesh& m, const std::string& path);

}  // namespace zs
