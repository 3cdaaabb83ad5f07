#include "render/volume/face_classes.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace zs {

std::vector<FaceClass> classify_faces(const TetMesh& m, const Topology& topo, const TransferFunction& tf,
                                      const View& view, FaceClassCounts* counts,
                                      std::vector<uint8_t>* tet_visible) {
  const size_t nt = m.num_tets();
  std::vector<uint8_t> visible(nt, 0);
  for (size_t t = 0; t < nt; ++t) {
    if (topo.tet_degenerate[t]) {
      ++counts->tets_degenerate;
      continue;
    }
    if (tf.transparent_over(topo.tet_scalar_range[t][0], topo.tet_scalar_range[t][1])) {
      ++counts->tets_invisible;
      continue;
    }
    visible[t] = 1;
  }

  std::vector<FaceClass> cls(topo.num_faces(), FaceClass::Culled);
  const glm::dvec3 eye = view.eye(), fwd = view.forward();
  for (uint32_t f = 0; f < topo.num_faces(); ++f) {
    const auto& ft = topo.face_tets[f];
    const bool v0 = visible[ft[0]] != 0;
    const bool v1 = ft[1] != kNoTet && visible[ft[1]] != 0;
    if (!v0 && !v1) {
      ++counts->faces_culled;
      continue;
    }
    if (v0 && v1) {
      cls[f] = FaceClass::Interior;
      continue;
    }
    // One visible side: find that tet's vertex off this face.
    const uint32_t t = v0 ? ft[0] : ft[1];
    const auto& fv = topo.faces[f];
    uint32_t opp = m.tets[t][0];
    for (uint32_t v : m.tets[t])
      if (v != fv[0] && v != fv[1] && v != fv[2]) opp = v;
    const glm::dvec3 a = m.points[fv[0]];
    const glm::dvec3 n = glm::cross(m.points[fv[1]] - a, m.points[fv[2]] - a);
    const double side_tet = glm::dot(n, m.points[opp] - a);
    // The side of the plane the rays come from: the eye (perspective), or
    // against the view direction (orthographic).
    const double side_eye = view.perspective() ? glm::dot(n, eye - a) : -glm::dot(n, fwd);
    // Rays cross from the eye's side to the other: they enter the tet iff the
    // tet is on the other side.
    cls[f] = (side_tet > 0) != (side_eye > 0) ? FaceClass::Entry : FaceClass::Exit;
  }
  if (tet_visible) *tet_visible = std::move(visible);
  return cls;
}

}  // namespace zs
