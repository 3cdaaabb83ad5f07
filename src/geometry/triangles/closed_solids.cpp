#include "geometry/triangles/closed_solids.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include <glm/geometric.hpp>

namespace zs {

namespace {

uint32_t find(std::vector<uint32_t>& parent, uint32_t a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

std::vector<int8_t> closed_solid_sides(const TriangleMesh& m, SolidCounts* counts) {
  const size_t T = m.num_tris();
  std::vector<int8_t> side(T, 0);
  // Directed edges (from, to, triangle), sorted by their undirected key, so
  // the uses of one edge are adjacent.
  struct Half {
    uint32_t lo, hi, tri;
    bool forward;  // from lo to hi
  };
  std::vector<Half> h;
  h.reserve(3 * T);
  for (uint32_t t = 0; t < T; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.tris[t][k], b = m.tris[t][(k + 1) % 3];
      h.push_back({std::min(a, b), std::max(a, b), t, a < b});
    }
  std::sort(h.begin(), h.end(), [](const Half& x, const Half& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri;
  });
  std::vector<uint32_t> parent(T);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<uint8_t> open(T, 0);  // the triangle has an edge that is not a matched pair
  for (size_t i = 0; i < h.size();) {
    size_t j = i + 1;
    while (j < h.size() && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
    const bool paired = j - i == 2 && h[i].forward != h[i + 1].forward && h[i].lo != h[i].hi;
    if (paired)
      parent[find(parent, h[i].tri)] = find(parent, h[i + 1].tri);
    else
      for (size_t k = i; k < j; ++k) open[h[k].tri] = 1;
    i = j;
  }
  // Per component: open anywhere, and six times its signed volume (relative
  // to one of its points, so far from the origin nothing cancels).
  std::vector<uint8_t> bad(T, 0);
  std::vector<double> vol(T, 0.0);
  std::vector<uint32_t> ref(T, UINT32_MAX);
  for (uint32_t t = 0; t < T; ++t) {
    const uint32_t r = find(parent, t);
    bad[r] |= open[t];
    if (ref[r] == UINT32_MAX) ref[r] = m.tris[t][0];
    const glm::dvec3 o = m.points[ref[r]];
    const glm::dvec3 a = m.points[m.tris[t][0]] - o, b = m.points[m.tris[t][1]] - o, c = m.points[m.tris[t][2]] - o;
    vol[r] += glm::dot(a, glm::cross(b, c));
  }
  SolidCounts c;
  for (uint32_t t = 0; t < T; ++t) {
    const uint32_t r = find(parent, t);
    const bool solid = !bad[r] && std::isfinite(vol[r]) && vol[r] != 0;
    if (r == t) {
      ++c.components;
      c.closed += solid;
      c.inward += solid && vol[r] < 0;
    }
    if (solid) side[t] = vol[r] > 0 ? 1 : -1;
  }
  if (counts) *counts = c;
  return side;
}

SolidCounts turn_solids_outward(TriangleMesh& m) {
  SolidCounts c;
  m.solid = closed_solid_sides(m, &c);
  for (size_t t = 0; t < m.num_tris(); ++t)
    if (m.solid[t] < 0) {
      std::swap(m.tris[t][1], m.tris[t][2]);
      m.solid[t] = 1;
    }
  return c;
}

}  // namespace zs
