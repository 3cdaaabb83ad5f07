// Small analytic meshes for tests: structured boxes split 5 tets per hex,
// optionally with cells removed (cavities, gaps) and a scalar field.
#pragma once

#include <algorithm>
#include <functional>

#include <glm/vec3.hpp>

#include "mesh/hex_split.h"
#include "mesh/tet_mesh.h"

namespace zs::test {

// n.x × n.y × n.z cells over [lo, hi]; keep(i, j, k) chooses cells;
// scalar(p) gives the point scalar.
inline TetMesh box_mesh(glm::ivec3 n, glm::dvec3 lo, glm::dvec3 hi,
                        const std::function<double(const glm::dvec3&)>& scalar,
                        const std::function<bool(int, int, int)>& keep = nullptr) {
  TetMesh m;
  const uint32_t nx = n.x + 1, ny = n.y + 1;
  for (int k = 0; k <= n.z; ++k)
    for (int j = 0; j <= n.y; ++j)
      for (int i = 0; i <= n.x; ++i) {
        const glm::dvec3 t{double(i) / n.x, double(j) / n.y, double(k) / n.z};
        const glm::dvec3 p = lo + t * (hi - lo);
        m.points.push_back(p);
        m.scalars.push_back(scalar(p));
      }
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i)
        if (!keep || keep(i, j, k)) append_hex_5tets(grid_hex(i, j, k, nx, ny), ((i + j + k) & 1) != 0, m.tets);
  m.scalar_name = "test";
  return m;
}

// Appends mesh b to a (points renumbered).
inline void append_mesh(TetMesh& a, const TetMesh& b) {
  const uint32_t base = uint32_t(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  a.scalars.insert(a.scalars.end(), b.scalars.begin(), b.scalars.end());
  for (Tet t : b.tets) {
    for (auto& v : t) v += base;
    a.tets.push_back(t);
  }
}

// Length of the ray o + t·d (t > 0) inside the box [lo, hi] (slab method).
inline double box_chord(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi) {
  double t0 = 0, t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return 0;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0 ? t1 - t0 : 0;
}

}  // namespace zs::test
