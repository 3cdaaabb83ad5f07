#include "geometry/triangles/clip_triangles.h"

#include <map>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

namespace zs {

TriangleClipCounts clip_triangles(TriangleMesh& m, const ClipRegion& region) {
  TriangleClipCounts counts;
  if (region.empty()) return counts;
  // The cut point of edge (a, b) by plane k, one per edge and plane.
  std::map<std::tuple<uint32_t, uint32_t, size_t>, uint32_t> cuts;
  auto cut_point = [&](uint32_t a, uint32_t b, size_t k) {
    if (a > b) std::swap(a, b);
    const ClipPlane& c = region.planes[k];
    const glm::dvec3 pa = m.points[a], pb = m.points[b];
    const double da = glm::dot(c.n, pa) + c.d, db = glm::dot(c.n, pb) + c.d;
    if (da == 0) return a;  // an end on the plane is the cut (no point twice)
    if (db == 0) return b;
    auto [it, fresh] = cuts.try_emplace({a, b, k}, 0);
    if (fresh) {
      const double t = da / (da - db);
      it->second = uint32_t(m.points.size());
      m.points.push_back(pa + t * (pb - pa));
    }
    return it->second;
  };
  std::vector<std::array<uint32_t, 3>> tris;
  std::vector<uint32_t> surface;
  for (size_t t = 0; t < m.tris.size(); ++t) {
    std::vector<uint32_t> poly(m.tris[t].begin(), m.tris[t].end()), next;
    bool was_cut = false;
    for (size_t k = 0; k < region.planes.size() && poly.size() >= 3; ++k) {
      const ClipPlane& c = region.planes[k];
      auto inside = [&](uint32_t v) { return glm::dot(c.n, m.points[v]) + c.d <= 0; };
      next.clear();
      for (size_t i = 0; i < poly.size(); ++i) {
        const uint32_t a = poly[i], b = poly[(i + 1) % poly.size()];
        const bool ia = inside(a), ib = inside(b);
        if (ia) next.push_back(a);
        if (ia != ib) next.push_back(cut_point(a, b, k));
        was_cut |= ia != ib;
      }
      poly.swap(next);
    }
    if (poly.size() < 3) {
      ++counts.dropped;
      continue;
    }
    counts.cut += was_cut;
    for (size_t i = 1; i + 1 < poly.size(); ++i) {  // a fan keeps the winding
      tris.push_back({poly[0], poly[i], poly[i + 1]});
      surface.push_back(m.surface[t]);
    }
  }
  m.tris = std::move(tris);
  m.surface = std::move(surface);
  m.normals.clear();
  m.solid.clear();
  m.two_sided.clear();
  return counts;
}

}  // namespace zs
