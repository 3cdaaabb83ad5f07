// The embedded default mesh: built in code so `zsweep` works with no files.
// A ball made by mapping a structured cube grid onto the sphere (so it is
// smooth, convex up to its faceting and conforming), 5 tets per hex, with a
// scalar that is a sum of three Gaussian blobs.
#pragma once

#include "geometry/tets/tet_mesh.h"

namespace zs {

TetMesh default_mesh(uint32_t cells_per_axis = 16);

}  // namespace zs
