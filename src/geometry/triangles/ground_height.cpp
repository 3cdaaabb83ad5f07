#include "geometry/triangles/ground_height.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

GroundPlacement auto_ground_height(const TriangleMesh& m) {
  GroundPlacement g;
  const Bounds b = triangle_bounds(m);
  if (b.empty) return g;
  g.height = b.lo.y;
  const glm::dvec3 e = b.hi - b.lo;
  // Relative to the whole extent, so a mesh of zero height still gets a gap.
  g.gap = 0.01 * std::max({e.x, e.y, e.z});
  if (!(g.gap > 0)) return g;  // every point the same: nothing lies flat
  const bool solids = m.solid.size() == m.num_tris();
  for (size_t t = 0; t < m.num_tris() && !g.lowered; ++t) {
    const glm::dvec3 n = face_normal(m, t);
    const double len = glm::length(n);
    if (!(len > 0) || std::abs(n.y) < 0.9 * len) continue;  // degenerate, or too steep to fight over an area
    if (solids && double(m.solid[t]) * n.y < 0) continue;      // a solid's bottom: never seen with the ground
    for (uint32_t v : m.tris[t]) g.lowered |= m.points[v].y <= b.lo.y + g.gap;
  }
  if (g.lowered) g.height = b.lo.y - g.gap;
  return g;
}

}  // namespace zs
