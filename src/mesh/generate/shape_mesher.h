// Mesh a catalog shape (shapes.h) with TetGen to roughly a target tet count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "mesh/tet_mesh.h"

namespace zs {

struct ShapeMeshOptions {
  std::string shape;        // a name from shape_catalog()
  size_t target_tets = 10000;
  uint64_t seed = 1;
  double quality = 1.414;   // TetGen radius-edge bound
  double tolerance = 0.1;   // accept counts within target * (1 +- tolerance)
};

// The count is steered through TetGen's max-volume bound: calibrated on a
// small run, then corrected from the full run's count (count ~ 1/max_volume).
// Throws std::invalid_argument for an unknown shape or a zero target.
TetMesh mesh_shape(const ShapeMeshOptions& opt);

}  // namespace zs
