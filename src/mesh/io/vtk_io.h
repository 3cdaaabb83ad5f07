// VTK-backed readers and writers. Kept in their own library so VTK headers
// never reach the renderer's hot translation units.
#pragma once

#include <string>

#include "mesh/io/mesh_io.h"

namespace zs {

// .vtu (XML) or .vtk (legacy) unstructured grid / any dataset VTK can read.
// Non-tet cells are split into tets; quadratic cells use their corner nodes.
TetMesh read_vtk(const std::string& path, const ReadOptions& opt);
// .vtu with the scalar as a point array named mesh.scalar_name (or "scalar").
void write_vtu(const std::string& path, const TetMesh& m);

// PLOT3D grid + solution (big-endian binary, IBLANK honoured), each hex split
// into 5 tets with alternating parity, duplicate points merged.
// opt.scalar: density (default) | velocity-magnitude | pressure | ...
TetMesh read_plot3d(const std::string& xyz_path, const ReadOptions& opt);

}  // namespace zs
