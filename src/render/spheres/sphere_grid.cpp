#include "render/spheres/sphere_grid.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace zs {

uint64_t SphereGrid::bytes() const {
  return offset.size() * 8 + ids.size() * 4 + centre.size() * sizeof(glm::dvec3) + radius.size() * 8 +
         (lo.size() + hi.size()) * sizeof(glm::dvec3);
}

uint32_t auto_sphere_grid(uint64_t count) {
  return uint32_t(std::clamp(std::round(std::cbrt(double(count) / 800.0)), 9.0, 64.0));
}

SphereGrid build_sphere_grid(const SphereSet& s, uint32_t n) {
  SphereGrid g;
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i < s.size(); ++i) {
    if (!drawable_sphere(s.centres[i], s.radii[i])) {
      ++g.invalid;
      continue;
    }
    lo = glm::min(lo, s.centres[i]);
    hi = glm::max(hi, s.centres[i]);
  }
  g.n = n ? n : auto_sphere_grid(s.size() - g.invalid);
  const uint32_t cells = g.cells();
  // The cell of a centre; clamped so the upper faces belong to the last cell.
  const glm::dvec3 ext = hi - lo;
  auto cell_of = [&](const glm::dvec3& c) {
    uint32_t k[3];
    for (int a = 0; a < 3; ++a) {
      const double u = ext[a] > 0 ? (c[a] - lo[a]) / ext[a] * g.n : 0.0;
      k[a] = uint32_t(std::clamp(u, 0.0, double(g.n - 1)));
    }
    return (k[2] * g.n + k[1]) * g.n + k[0];
  };
  // Counting sort by cell: ids stay ascending within each cell.
  std::vector<uint32_t> cell(s.size(), UINT32_MAX);
  g.offset.assign(cells + 1, 0);
  for (size_t i = 0; i < s.size(); ++i) {
    if (!drawable_sphere(s.centres[i], s.radii[i])) continue;
    cell[i] = cell_of(s.centres[i]);
    ++g.offset[cell[i] + 1];
  }
  for (uint32_t k = 0; k < cells; ++k) g.offset[k + 1] += g.offset[k];
  g.ids.resize(g.offset[cells]);
  g.centre.resize(g.offset[cells]);
  g.radius.resize(g.offset[cells]);
  std::vector<uint64_t> next(g.offset.begin(), g.offset.end() - 1);
  g.lo.assign(cells, glm::dvec3(INFINITY));
  g.hi.assign(cells, glm::dvec3(-INFINITY));
  for (size_t i = 0; i < s.size(); ++i) {
    if (cell[i] == UINT32_MAX) continue;
    const uint32_t k = cell[i];
    g.centre[next[k]] = s.centres[i];
    g.radius[next[k]] = s.radii[i];
    g.ids[next[k]++] = uint32_t(i);
    // The sphere's box rounded outward: a radius below the centre's ulp
    // would otherwise vanish from it (c - r == c), and the cell would project
    // to its centre pixel only and be culled by what covers that pixel (a
    // fuzzing finding). One ulp wider is still a box of the sphere.
    const glm::dvec3 c = s.centres[i], r(s.radii[i]);
    const glm::dvec3 lo_i(std::nextafter(c.x - r.x, -INFINITY), std::nextafter(c.y - r.y, -INFINITY),
                          std::nextafter(c.z - r.z, -INFINITY));
    const glm::dvec3 hi_i(std::nextafter(c.x + r.x, INFINITY), std::nextafter(c.y + r.y, INFINITY),
                          std::nextafter(c.z + r.z, INFINITY));
    g.lo[k] = glm::min(g.lo[k], lo_i);
    g.hi[k] = glm::max(g.hi[k], hi_i);
  }
  return g;
}

}  // namespace zs
