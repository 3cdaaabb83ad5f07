#include "geometry/tets/tet_mesh.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

double signed_volume6(const TetMesh& m, const Tet& t) {
  const glm::dvec3& a = m.points[t[0]];
  return glm::dot(m.points[t[1]] - a,
                  glm::cross(m.points[t[2]] - a, m.points[t[3]] - a));
}

void average_cell_scalars_onto_points(TetMesh& m) {
  std::vector<double> sum(m.num_points(), 0.0);
  std::vector<uint32_t> n(m.num_points(), 0);
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (uint32_t v : m.tets[t]) sum[v] += m.cell_scalars[t], ++n[v];
  for (size_t v = 0; v < sum.size(); ++v) sum[v] = n[v] ? sum[v] / n[v] : 0.0;
  m.scalars = std::move(sum);
  std::vector<double>().swap(m.cell_scalars);
  m.notes.push_back("scalar '" + (m.scalar_name.empty() ? std::string("scalar") : m.scalar_name) +
                    "' is cell data: averaged onto points (mean over each point's tets)");
}

double Bounds::half_diagonal() const {
  if (empty) return 0.0;
  const glm::dvec3 e = 0.5 * hi - 0.5 * lo;  // no overflow: each half is finite
  const double m = std::max(e.x, std::max(e.y, e.z));
  return m > 0 ? m * glm::length(e / m) : 0.0;
}

Bounds bounds_of(const TetMesh& m) {
  Bounds b;
  for (const glm::dvec3& p : m.points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    if (b.empty) {
      b.lo = b.hi = p;
      b.empty = false;
    } else {
      b.lo = glm::min(b.lo, p);
      b.hi = glm::max(b.hi, p);
    }
  }
  return b;
}

}  // namespace zs
