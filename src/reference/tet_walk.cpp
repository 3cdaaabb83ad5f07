#include "reference/tet_walk.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "reference/boundary_hits.h"

namespace zs {

bool tet_exit(const TetMesh& m, const Topology& topo, uint32_t tet, uint32_t entered_face, const glm::dvec3& o,
              const glm::dvec3& d, int* exit_local, double* t_exit, double lambda_o[4], double dlambda[4]) {
  const Tet& tv = m.tets[tet];
  const glm::dvec3 p0 = m.points[tv[0]];
  const glm::dvec3 e1 = m.points[tv[1]] - p0, e2 = m.points[tv[2]] - p0, e3 = m.points[tv[3]] - p0;
  // Rows of the inverse edge matrix are the gradients of lambda_1..3.
  const glm::dvec3 c23 = glm::cross(e2, e3), c31 = glm::cross(e3, e1), c12 = glm::cross(e1, e2);
  const double det = glm::dot(e1, c23);
  const double L = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
  if (!(std::abs(det) > 1e-12 * L * std::sqrt(L))) return false;
  const glm::dvec3 g[3] = {c23 / det, c31 / det, c12 / det};
  const glm::dvec3 po = o - p0;
  double l_sum = 0, d_sum = 0;
  for (int k = 1; k < 4; ++k) {
    lambda_o[k] = glm::dot(g[k - 1], po);
    dlambda[k] = glm::dot(g[k - 1], d);
    l_sum += lambda_o[k];
    d_sum += dlambda[k];
  }
  lambda_o[0] = 1.0 - l_sum;
  dlambda[0] = -d_sum;
  // Leave through face k (opposite vertex k) where lambda_k falls to zero.
  int best = -1;
  double best_t = INFINITY;
  for (int k = 0; k < 4; ++k) {
    if (topo.tet_faces[tet][size_t(k)] == entered_face || !(dlambda[k] < 0)) continue;
    const double tk = -lambda_o[k] / dlambda[k];
    if (tk < best_t) best_t = tk, best = k;
  }
  if (best < 0) return false;
  *exit_local = best;
  *t_exit = best_t;
  return true;
}

int flat_tet_pass(const TetMesh& m, const Topology& topo, uint32_t tet, uint32_t entered_face, const glm::dvec3& o,
                  const glm::dvec3& d) {
  const Tet& tv = m.tets[tet];
  for (int k = 0; k < 4; ++k) {
    const uint32_t f = topo.tet_faces[tet][size_t(k)];
    if (f == entered_face) continue;
    const glm::dvec3 &a = m.points[tv[(k + 1) % 4]], &b = m.points[tv[(k + 2) % 4]], &c = m.points[tv[(k + 3) % 4]];
    double t;
    if (line_hits_triangle(o, d, a, b, c, &t)) return k;
  }
  return -1;
}

}  // namespace zs
