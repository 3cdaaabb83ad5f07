// The regular cell grid over a sphere set (spheres digest §2.2.1): built once per
// set (the data are static), reused by every frame's culling. A sphere
// belongs to the cell holding its centre; a cell's box is the box of its
// spheres, radii included, so it may overlap its neighbours.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "geometry/spheres/sphere_set.h"

namespace zs {

struct SphereGrid {
  uint32_t n = 0;                  // cells per axis (n³ cells)
  std::vector<uint64_t> offset;    // n³ + 1: cell k holds ids[offset[k], offset[k+1])
  std::vector<uint32_t> ids;       // sphere ids, grouped by cell, ascending within a cell
  // Each entry's centre and radius, in the same order: the per-frame loops
  // stream through these instead of gathering from the set.
  std::vector<glm::dvec3> centre;
  std::vector<double> radius;
  std::vector<glm::dvec3> lo, hi;  // per cell: the box of its spheres (empty cells: lo > hi)
  uint64_t invalid = 0;            // spheres left out: non-finite centre, radius not > 0 or not finite

  uint32_t cells() const { return n * n * n; }
  uint64_t count(uint32_t k) const { return offset[k + 1] - offset[k]; }
  uint64_t bytes() const;
};

// Bins every drawable sphere of `s` into an n³ grid over the box of the
// centres; n = 0 picks auto_sphere_grid() of the drawable count.
SphereGrid build_sphere_grid(const SphereSet& s, uint32_t n);

// The grid resolution `render.grid: "auto"` takes for `count` spheres: about
// 800 spheres a cell (cbrt(count / 800)), at least 9 (the spheres digest's 9³, §2.2.1) and
// at most 64. Finer cells let occlusion culling drop more of a dense set
// before its spheres are touched one by one (docs/spheres-bench.md: C4 at
// 32³ takes half the time of 9³); a cell costs a box test per frame.
uint32_t auto_sphere_grid(uint64_t count);

// True when the sphere can be drawn (finite centre, finite radius > 0).
inline bool drawable_sphere(const glm::dvec3& c, double r) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(r) && r > 0;
}

}  // namespace zs
