// Which triangles bound a closed solid, and which way it faces. A connected
// set of triangles (through shared edges) bounds a solid when every edge of it
// is used by exactly two of its triangles, in opposite directions (a closed,
// consistently oriented 2-manifold); its signed volume tells whether the
// counter-clockwise fronts face out (+1) or in (−1). Along any ray from
// outside such a solid, entries and exits alternate starting with an entry,
// so the nearest hit is on a face turned towards the ray's origin: a
// directional light's map needs only those (shadow_map.cpp), and the camera
// never sees a solid's back faces from outside (back-face culling is lossless
// there, and only there: an open surface shows both sides).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/triangles/triangle_mesh.h"

namespace zs {

struct SolidCounts {
  size_t components = 0;  // connected sets (through edges used by two triangles in opposite directions)
  size_t closed = 0;      // of those, closed solids
  size_t inward = 0;      // of those, wound with their fronts facing in
};

// Per triangle: +1 (bounds a closed solid, fronts out), −1 (fronts in), 0 (any
// other: open, non-manifold, inconsistently oriented, non-finite, or of zero
// volume). `counts`, when given, gets the component counts.
std::vector<int8_t> closed_solid_sides(const TriangleMesh& m, SolidCounts* counts = nullptr);

// Reverses the triangles of every closed solid wound inward, so every solid's
// fronts face out (a file wound the other way round renders as its
// outward twin), and sets m.solid (then 0 or +1 only). Returns the counts
// from before the turn (`inward`: the solids turned). Normals are the
// caller's to recompute.
SolidCounts turn_solids_outward(TriangleMesh& m);

}  // namespace zs
