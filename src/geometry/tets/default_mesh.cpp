#include "geometry/tets/default_mesh.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/tets/hex_split.h"

namespace zs {

TetMesh default_mesh(uint32_t n) {
  TetMesh m;
  const uint32_t nn = n + 1;
  m.points.reserve(size_t(nn) * nn * nn);
  for (uint32_t k = 0; k < nn; ++k)
    for (uint32_t j = 0; j < nn; ++j)
      for (uint32_t i = 0; i < nn; ++i) {
        // Cube [-1,1]^3 onto the unit ball; this map keeps cells well shaped
        // (no collapse at the corners, unlike normalising the position).
        const double x = -1.0 + 2.0 * i / n, y = -1.0 + 2.0 * j / n, z = -1.0 + 2.0 * k / n;
        const double x2 = x * x, y2 = y * y, z2 = z * z;
        m.points.push_back({x * std::sqrt(1 - y2 / 2 - z2 / 2 + y2 * z2 / 3),
                            y * std::sqrt(1 - z2 / 2 - x2 / 2 + z2 * x2 / 3),
                            z * std::sqrt(1 - x2 / 2 - y2 / 2 + x2 * y2 / 3)});
      }
  const glm::dvec3 centre[3] = {{0.35, 0.2, 0.1}, {-0.4, -0.25, 0.2}, {0.05, -0.1, -0.45}};
  const double width[3] = {0.3, 0.25, 0.2};
  const double weight[3] = {1.0, 0.8, 0.6};
  m.scalars.reserve(m.points.size());
  for (const glm::dvec3& p : m.points) {
    double s = 0.0;
    for (int g = 0; g < 3; ++g) {
      const glm::dvec3 d = p - centre[g];
      s += weight[g] * std::exp(-glm::dot(d, d) / (2 * width[g] * width[g]));
    }
    m.scalars.push_back(s);
  }
  m.scalar_name = "blobs";
  m.tets.reserve(size_t(5) * n * n * n);
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i)
        append_hex_5tets(grid_hex(i, j, k, nn, nn), ((i + j + k) & 1) != 0, m.tets);
  m.notes.push_back("embedded default mesh: ball from a " + std::to_string(n) + "^3 hex grid, 5 tets per hex");
  return m;
}

}  // namespace zs
