// Where the automatic ground plane goes under a mesh. At the mesh's lowest y
// it touches the mesh, which is right for a mesh standing on a few points or
// on a closed solid's bottom (whose faces point down, so from above only the
// ground is drawn and from below only the bottom). A part of the mesh lying
// flat within a hair of that height and seen from above (a flat or thin
// open surface, an upward face) would fight the ground for the same pixels:
// then the ground goes a clear gap lower.
#pragma once

#include "geometry/triangles/triangle_mesh.h"

namespace zs {

struct GroundPlacement {
  double height = 0;     // the ground's y
  bool lowered = false;  // put `gap` below the lowest y (else at it)
  double gap = 0;        // 1 % of the mesh's largest extent
};

// For `m`, the surfaces alone with m.solid set (closed_solids.h). A triangle
// fights the ground when it is nearly level (its normal within about 26° of
// vertical), has a corner within `gap` of the lowest y, and is not a closed
// solid's face turned down. An empty mesh: height 0.
GroundPlacement auto_ground_height(const TriangleMesh& m);

}  // namespace zs
