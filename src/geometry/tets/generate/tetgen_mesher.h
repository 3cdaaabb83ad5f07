// Tetrahedralize a PLC (closed surface, possibly with cavities) with TetGen.
#pragma once

#include <cstddef>

#include "geometry/tets/generate/plc.h"
#include "geometry/tets/tet_mesh.h"

namespace zs {

struct TetgenOptions {
  double quality = 1.414;        // radius-edge ratio bound (-q), >= 1.1; 0 disables
  double max_volume = 0.0;       // max tet volume (-a); <= 0 = unbounded
  bool preserve_surface = false; // -Y: no Steiner points on the boundary
  size_t max_tets = 5000000;     // the work bound below; 0 = none
};

// Runs TetGen quietly ("pQ" + switches). Throws std::runtime_error with
// TetGen's last error line (e.g. self-intersecting input).
// Bounded by max_tets: a max_volume that forces more tets into a closed
// triangle surface (its volume / max_volume) is refused up front
// (std::invalid_argument), and TetGen may add at most max_tets / 4 points
// (-S; a tet mesh has about 6 tets per point), past which it throws.
TetMesh tetrahedralize(const Plc& plc, const TetgenOptions& opt);

}  // namespace zs
