#include "render/volume/near_clip.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace zs {

namespace {

class EdgePoints {
 public:
  EdgePoints(const TetMesh& m, const View& view, const std::vector<ScreenVertex>& sv, double z_near)
      : m_(m), view_(view), sv_(sv), zn_(z_near), next_id_(uint32_t(sv.size())) {}

  // The point where edge (a, b) crosses z = z_near (a in front, b behind or
  // the reverse), with its scalar; one id per edge.
  ScreenVertex at(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    const uint64_t key = (uint64_t(a) << 32) | b;
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    // Interpolate in depth: view depth is affine in world position.
    const double za = sv_[a].z, zb = sv_[b].z;
    const double t = (zn_ - za) / (zb - za);
    const glm::dvec3 p = m_.points[a] + t * (m_.points[b] - m_.points[a]);
    const ViewPoint vp = view_.project(p);
    const ScreenVertex v{vp.x, vp.y, zn_, sv_[a].s + t * (sv_[b].s - sv_[a].s), next_id_++};
    cache_.emplace(key, v);
    return v;
  }

 private:
  const TetMesh& m_;
  const View& view_;
  const std::vector<ScreenVertex>& sv_;
  double zn_;
  uint32_t next_id_;
  std::unordered_map<uint64_t, ScreenVertex> cache_;
};

// Convex polygon (3 or 4 vertices, in order) -> triangles, fanned from the
// vertex with the smallest id so the diagonal is the same from any side.
void emit_polygon(const ScreenVertex* p, int n, FaceClass cls, std::vector<NearTriangle>* out) {
  int k0 = 0;
  for (int k = 1; k < n; ++k)
    if (p[k].id < p[k0].id) k0 = k;
  for (int k = 1; k + 1 < n; ++k)
    out->push_back({{p[k0], p[(k0 + k) % n], p[(k0 + k + 1) % n]}, cls});
}

}  // namespace

void clip_at_near_plane(const TetMesh& m, const Topology& topo, const View& view,
                        const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                        const std::vector<uint8_t>& tet_visible, double z_near, std::vector<NearTriangle>* out,
                        std::vector<uint8_t>* clipped) {
  EdgePoints pts(m, view, sv, z_near);
  auto behind = [&](uint32_t v) { return !(sv[v].z > z_near); };

  // Faces reaching behind the plane: keep their front part.
  for (uint32_t f = 0; f < topo.num_faces(); ++f) {
    if (cls[f] == FaceClass::Culled) continue;
    const auto fv = topo.face(f);
    const int nb = behind(fv[0]) + behind(fv[1]) + behind(fv[2]);
    if (nb == 0) continue;
    (*clipped)[f] = 1;
    if (nb == 3) continue;
    // Walk the triangle's edges, keeping front vertices and crossings.
    ScreenVertex poly[4];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = fv[k], b = fv[(k + 1) % 3];
      if (!behind(a)) poly[n++] = sv[a];
      if (behind(a) != behind(b)) poly[n++] = pts.at(a, b);
    }
    if (m.has_cell_scalars()) {  // cell data: the face's value (face_classes.h)
      const double c = m.cell_scalars[value_from_tet1(cls[f]) ? topo.tet1(f) : topo.tet0(f)];
      for (int k = 0; k < n; ++k) poly[k].s = c;
    }
    emit_polygon(poly, n, cls[f], out);
  }

  // Cross-sections of visible tets cut by the plane: entry faces at z_near.
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (uint32_t t = 0; t < m.num_tets(); ++t) {
    if (!tet_visible[t]) continue;
    const Tet& tet = m.tets[t];
    const int nb = behind(tet[0]) + behind(tet[1]) + behind(tet[2]) + behind(tet[3]);
    if (nb == 0 || nb == 4) continue;
    ScreenVertex cut[4];
    int n = 0;
    for (const auto& e : kEdges)
      if (behind(tet[e[0]]) != behind(tet[e[1]])) cut[n++] = pts.at(tet[e[0]], tet[e[1]]);
    if (n == 4) {
      // A quad: order its corners around the section (sort by angle about
      // the centroid in screen space; the section is planar and convex).
      double cx = 0, cy = 0;
      for (int k = 0; k < 4; ++k) cx += cut[k].x / 4, cy += cut[k].y / 4;
      std::sort(cut, cut + 4, [&](const ScreenVertex& a, const ScreenVertex& b) {
        return std::atan2(a.y - cy, a.x - cx) < std::atan2(b.y - cy, b.x - cx);
      });
    }
    if (m.has_cell_scalars())
      for (int k = 0; k < n; ++k) cut[k].s = m.cell_scalars[t];
    emit_polygon(cut, n, FaceClass::Entry, out);
  }
}

}  // namespace zs
