// VTK-backed readers and writers. Kept in their own library so VTK headers
// never reach the renderer's hot translation units.
#pragma once

#include <cstdint>
#include <string>

#include "geometry/tets/io/mesh_io.h"

namespace zs {

// .vtu (XML) or .vtk (legacy) unstructured grid / any dataset VTK can read.
// Non-tet cells are split into tets; quadratic cells use their corner nodes.
TetMesh read_vtk(const std::string& path, const ReadOptions& opt);
// An unstructured grid's arrays as VTK 9 holds them (the Python module's
// vtkUnstructuredGrid, seen as numpy views): points x,y,z per point, cell
// offsets (num_cells + 1) into the connectivity, VTK cell types, an optional
// point or cell scalar. Borrowed, not copied, while the mesh is made.
struct VtkCells {
  const double* points = nullptr;
  int64_t num_points = 0;
  const int64_t* offsets = nullptr;
  const int64_t* connectivity = nullptr;
  int64_t num_connectivity = 0;
  const int64_t* types = nullptr;
  int64_t num_cells = 0;
  const double* scalars = nullptr;       // num_points values, or null
  const double* cell_scalars = nullptr;  // else num_cells values, or null
  bool cell_scalars_float = false;       // they came as float32: averaged in float, as the reader averages a file's
  ScalarAssociation association = ScalarAssociation::Auto;  // as a file's (ReadOptions)
};
// The same tets read_vtk makes of a file with these cells; `name` stands for
// the file in messages.
TetMesh tet_mesh_from_cells(const VtkCells& cells, const std::string& name);

// .vtu with the scalar as a point (or cell) array named mesh.scalar_name (or
// "scalar").
void write_vtu(const std::string& path, const TetMesh& m);

// PLOT3D grid + solution (big-endian binary, IBLANK honoured), each hex split
// into 5 tets with alternating parity, duplicate points merged.
// opt.scalar: density (default; when it is constant, the first function
// that varies) | velocity-magnitude | pressure | ...
TetMesh read_plot3d(const std::string& xyz_path, const ReadOptions& opt);

}  // namespace zs
