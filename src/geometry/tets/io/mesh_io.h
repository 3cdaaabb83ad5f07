// Format dispatch: read or write a tet mesh by file name.
//   .off             classic tet OFF (off_io.h, hand-written)
//   .zsm             zsweep's binary mesh (zsm_io.h, hand-written)
//   .vtu .vtk        VTK XML / legacy (vtk_io.h, via VTK readers)
//   *xyz.bin + q     PLOT3D (plot3d_io.h, via VTK's PLOT3D reader)
//   .node / .ele     TetGen (tetgen_io.h, via the TetGen library)
// Every failure is a zs::FileError whose message names the file.
#pragma once

#include <cstdint>
#include <string>

#include "geometry/tets/tet_mesh.h"

namespace zs {

// Where the scalar lives. Auto: as the array is stored (point data stay on
// the points, cell data on the tets, each tet keeping its cell's value);
// Point / Cell: only arrays of that association; CellToPoint: point data as
// stored, cell data averaged onto the points (vtkCellDataToPointData).
enum class ScalarAssociation : uint8_t { Auto, Point, Cell, CellToPoint };
const char* to_string(ScalarAssociation a);
bool parse_association(const std::string& s, ScalarAssociation* out);

struct ReadOptions {
  std::string scalar;  // array (or PLOT3D function) to use; "" = default
  std::string q_path;  // PLOT3D solution file; required for PLOT3D grids
  ScalarAssociation association = ScalarAssociation::Auto;
};

enum class MeshFormat { Off, Zsm, Vtu, VtkLegacy, Plot3d, TetGen, Unknown };

MeshFormat format_of(const std::string& path, const ReadOptions& opt = {});

TetMesh read_mesh(const std::string& path, const ReadOptions& opt = {});

// Writes to a temporary name beside `path`, renames on success, so a failed
// write never leaves a partial file behind.
void write_mesh(const std::string& path, const TetMesh& m);

}  // namespace zs
