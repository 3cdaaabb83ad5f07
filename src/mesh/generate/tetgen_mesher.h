// Tetrahedralize a PLC (closed surface, possibly with cavities) with TetGen.
#pragma once

#include "mesh/generate/plc.h"
#include "mesh/tet_mesh.h"

namespace zs {

struct TetgenOptions {
  double quality = 1.414;        // radius-edge ratio bound (-q), >= 1.1; 0 disables
  double max_volume = 0.0;       // max tet volume (-a); <= 0 = unbounded
  bool preserve_surface = false; // -Y: no Steiner points on the boundary
};

// Runs TetGen quietly ("pQ" + switches). Throws std::runtime_error with
// TetGen's last error line (e.g. self-intersecting input).
TetMesh tetrahedralize(const Plc& plc, const TetgenOptions& opt);

}  // namespace zs
