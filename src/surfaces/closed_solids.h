// Which triangles bound a closed solid, and which way it faces. A connected
// set of triangles (through shared edges) bounds a solid when every edge of it
// is used by exactly two of its triangles, in opposite directions (a closed,
// consistently oriented 2-manifold); its signed volume tells whether the
// counter-clockwise fronts face out (+1) or in (−1). Along any ray from
// outside such a solid, entries and exits alternate starting with an entry,
// so the nearest hit is on a face turned towards the ray's origin: a
// directional light's map needs only those (shadow_map.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "surfaces/triangle_mesh.h"

namespace zs {

// Per triangle: +1 (bounds a closed solid, fronts out), −1 (fronts in), 0 (any
// other: open, non-manifold, inconsistently oriented, non-finite, or of zero
// volume).
std::vector<int8_t> closed_solid_sides(const TriangleMesh& m);

}  // namespace zs
