#include "geometry/triangles/triangle_mesh.h"

#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace zs {

namespace {
bool finite(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
}  // namespace

void append_mesh(TriangleMesh& a, const TriangleMesh& b, uint32_t surface_id) {
  const uint32_t base = uint32_t(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  a.tris.reserve(a.tris.size() + b.tris.size());
  for (const auto& t : b.tris) a.tris.push_back({t[0] + base, t[1] + base, t[2] + base});
  a.surface.insert(a.surface.end(), b.tris.size(), surface_id);
  a.normals.clear();  // stale: recompute after the last append
  a.solid.clear();
  a.two_sided.clear();
}

glm::dvec3 face_normal(const TriangleMesh& m, size_t t) {
  const auto& v = m.tris[t];
  const glm::dvec3 &a = m.points[v[0]], &b = m.points[v[1]], &c = m.points[v[2]];
  return glm::cross(b - a, c - a);
}

void compute_point_normals(TriangleMesh& m) {
  m.normals.assign(m.points.size(), glm::dvec3(0.0));
  for (size_t t = 0; t < m.tris.size(); ++t) {
    const glm::dvec3 n = face_normal(m, t);
    if (!finite(n)) continue;
    for (uint32_t v : m.tris[t]) m.normals[v] += n;
  }
  for (glm::dvec3& n : m.normals) {
    const double l = glm::length(n);
    n = l > 0 && std::isfinite(l) ? n / l : glm::dvec3(0.0);
  }
}

Bounds triangle_bounds(const TriangleMesh& m) {
  Bounds b;
  for (const auto& t : m.tris)
    for (uint32_t v : t) {
      const glm::dvec3& p = m.points[v];
      if (!finite(p)) continue;
      b.lo = b.empty ? p : glm::min(b.lo, p);
      b.hi = b.empty ? p : glm::max(b.hi, p);
      b.empty = false;
    }
  return b;
}

size_t count_degenerate_tris(const TriangleMesh& m) {
  size_t n = 0;
  for (size_t t = 0; t < m.tris.size(); ++t) {
    const glm::dvec3 f = face_normal(m, t);
    n += !(finite(f) && (f.x != 0 || f.y != 0 || f.z != 0));
  }
  return n;
}

}  // namespace zs
