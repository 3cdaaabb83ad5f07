#include "render/reference/tet_walk.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>


namespace zs {

bool tet_exit(const TetMesh& m, const SolidFaces& solid, uint32_t tet, uint32_t entered_face, const glm::dvec3& o,
              const glm::dvec3& d, int* exit_local, double* t_exit, double lambda_o[4], double dlambda[4]) {
  const Tet& tv = m.tets[tet];
  const glm::dvec3 p0 = m.points[tv[0]];
  const glm::dvec3 e1 = m.points[tv[1]] - p0, e2 = m.points[tv[2]] - p0, e3 = m.points[tv[3]] - p0;
  // Rows of the inverse edge matrix are the gradients of lambda_1..3.
  const glm::dvec3 c23 = glm::cross(e2, e3), c31 = glm::cross(e3, e1), c12 = glm::cross(e1, e2);
  // The walk never enters a flat tet (SolidFaces); this only guards the division.
  const double det = glm::dot(e1, c23);
  if (det == 0) return false;
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
    if (solid.tet_faces[tet][size_t(k)] == entered_face || !(dlambda[k] < 0)) continue;
    const double tk = -lambda_o[k] / dlambda[k];
    if (tk < best_t) best_t = tk, best = k;
  }
  if (best < 0) return false;
  *exit_local = best;
  *t_exit = best_t;
  return true;
}

bool tet_is_flat(const TetMesh& m, const Tet& t) {
  const glm::dvec3 p0 = m.points[t[0]];
  const glm::dvec3 e1 = m.points[t[1]] - p0, e2 = m.points[t[2]] - p0, e3 = m.points[t[3]] - p0;
  const double L = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
  return !(std::abs(glm::dot(e1, glm::cross(e2, e3))) > 1e-12 * L * std::sqrt(L));
}

SolidFaces build_solid_faces(const TetMesh& m, const Topology& topo) {
  SolidFaces s;
  s.flat.resize(m.num_tets());
  for (size_t t = 0; t < m.num_tets(); ++t) s.flat[t] = tet_is_flat(m, m.tets[t]);
  s.tet_faces = build_tet_faces(m, topo);
  s.tets.resize(topo.num_faces());
  auto add = [&](uint32_t f, uint32_t t) {
    auto& ft = s.tets[f];
    if (s.flat[t] || ft[0] == t || ft[1] == t) return;
    if (ft[0] == kNoTet) ft[0] = t;
    else if (ft[1] == kNoTet) ft[1] = t;
  };
  for (uint32_t f = 0; f < topo.num_faces(); ++f) {
    s.tets[f] = {kNoTet, kNoTet};
    add(f, topo.tet0(f));
    if (topo.tet1(f) != kNoTet) add(f, topo.tet1(f));
  }
  // Faces with more than two tets keep only two in the topology: find the rest.
  if (!topo.nonmanifold_faces.empty()) {
    std::vector<uint8_t> nm(topo.num_faces(), 0);
    for (uint32_t f : topo.nonmanifold_faces) nm[f] = 1;
    for (uint32_t t = 0; t < m.num_tets(); ++t)
      for (uint32_t f : s.tet_faces[t])
        if (nm[f]) add(f, t);
  }
  return s;
}

}  // namespace zs
