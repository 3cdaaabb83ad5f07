// The scalar a VTK dataset gives a tet mesh (vtk_scalar.cpp); VTK types
// only by name, for the readers in this directory.
#pragma once

#include <string>
#include <vector>

#include "geometry/tets/io/mesh_io.h"
#include "geometry/tets/io/vtk_capture.h"
#include "geometry/tets/tet_mesh.h"

class vtkDataSet;

namespace zs::detail {

// One value per point of `ds`, or per cell (cell true), as opt.scalar names
// it or by default and as opt.association allows; empty if it has no data
// arrays at all. Names the choice in m.scalar_name, m.scalar_choice and
// m.notes. Throws FileError naming `path` for a name that is not there,
// listing the arrays that are.
struct PickedScalar {
  std::vector<double> values;
  bool cell = false;
};
PickedScalar pick_scalar(vtkDataSet* ds, const ReadOptions& opt, const std::string& path, TetMesh& m,
                         VtkMessageCapture& capture);

}  // namespace zs::detail
