#include "lighting/triangle_projection.h"

#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>


namespace zs {

namespace {

bool finite(const ScreenVertex& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void project_triangles(const TriangleMesh& m, const View& view, const ProjectOptions& opt, ProjectedTriangles* out,
                       ProjectCounts* counts) {
  ProjectCounts c;
  c.triangles = m.num_tris();
  out->perspective = view.perspective();
  out->verts.resize(m.num_points());
  out->corners.clear();
  out->source.clear();
  for (size_t i = 0; i < m.num_points(); ++i) {
    const ViewPoint p = view.project(m.points[i]);
    out->verts[i] = {p.x, p.y, p.z, 0.0, uint32_t(i)};
  }
  const double W = view.width(), H = view.height();
  // The box of a triangle's corners holds no pixel centre of the image.
  auto outside = [&](const ScreenVertex* v) {
    const double x0 = std::min({v[0].x, v[1].x, v[2].x}), x1 = std::max({v[0].x, v[1].x, v[2].x});
    const double y0 = std::min({v[0].y, v[1].y, v[2].y}), y1 = std::max({v[0].y, v[1].y, v[2].y});
    return x1 < 0 || x0 > W - 1 || y1 < 0 || y0 > H - 1 || std::ceil(x0) > std::floor(x1) ||
           std::ceil(y0) > std::floor(y1);
  };
  // Keeps or culls a triangle given as screen vertices; true when kept.
  auto consider = [&](const ScreenVertex* v, bool* back) {
    const double det = screen_det(v);
    if (det == 0 || !std::isfinite(det)) return false;
    *back = det > 0;
    return true;
  };
  std::unordered_map<uint64_t, uint32_t> cut_ids;
  const glm::dvec3 eye = view.eye(), f = view.forward(), r = view.right(), u = view.up();
  for (size_t t = 0; t < m.num_tris(); ++t) {
    if (opt.skip && (*opt.skip)[t]) {
      ++c.skipped;
      continue;
    }
    const auto& tri = m.tris[t];
    const bool cull_back = opt.cull_back && !(m.two_sided.size() == m.num_tris() && m.two_sided[t]);
    const ScreenVertex v[3] = {out->verts[tri[0]], out->verts[tri[1]], out->verts[tri[2]]};
    if (!finite(v[0]) || !finite(v[1]) || !finite(v[2])) {
      ++c.degenerate;
      continue;
    }
    const int behind = (v[0].z < opt.z_near) + (v[1].z < opt.z_near) + (v[2].z < opt.z_near);
    if (behind == 3) {
      ++c.view_culled;
      continue;
    }
    if (behind == 0) {
      bool back;
      if (!consider(v, &back)) {
        ++c.degenerate;
        continue;
      }
      if (back && cull_back) {
        ++c.back_culled;
        continue;
      }
      c.back_two_sided += back && opt.cull_back;
      if (opt.cull_view && outside(v)) {
        ++c.view_culled;
        continue;
      }
      out->corners.push_back({tri[0], tri[1], tri[2]});
      out->source.push_back(uint32_t(t));
      continue;
    }
    // Clip in camera space (Sutherland–Hodgman against z >= z_near); a cut
    // point is computed from the inside end towards the outside end, as
    // raster/triangle_clip.h does, so both triangles of an edge agree.
    glm::dvec3 cam[3];
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 d = m.points[tri[k]] - eye;
      cam[k] = {glm::dot(d, r), glm::dot(d, u), glm::dot(d, f)};
    }
    uint32_t ids[4];
    ScreenVertex sv[4];
    int n = 0;
    for (int q = 0; q < 3; ++q) {
      const int e = (q + 1) % 3;
      const bool qin = cam[q].z >= opt.z_near, ein = cam[e].z >= opt.z_near;
      if (qin) {
        ids[n] = tri[q];
        sv[n++] = out->verts[tri[q]];
      }
      if (qin == ein) continue;
      const int i = qin ? q : e, o = qin ? e : q;  // inside and outside ends
      const uint64_t key = (uint64_t(std::min(tri[i], tri[o])) << 32) | uint64_t(std::max(tri[i], tri[o]));
      auto it = cut_ids.find(key);
      if (it == cut_ids.end()) {
        const double s = (cam[i].z - opt.z_near) / (cam[i].z - cam[o].z);
        double X = cam[i].x + s * (cam[o].x - cam[i].x), Y = cam[i].y + s * (cam[o].y - cam[i].y);
        if (view.perspective()) {
          X /= opt.z_near;
          Y /= opt.z_near;
        }
        const uint32_t id = uint32_t(out->verts.size());
        out->verts.push_back({X * view.scale_x() + view.offset_x(), view.offset_y() - Y * view.scale_y(),
                              opt.z_near, 0.0, id});
        it = cut_ids.emplace(key, id).first;
      }
      ids[n] = it->second;
      sv[n++] = out->verts[it->second];
    }
    if (n < 3) {
      ++c.view_culled;
      continue;
    }
    ++c.near_clipped;
    for (int k = 1; k + 1 < n; ++k) {
      const ScreenVertex fan[3] = {sv[0], sv[k], sv[k + 1]};
      bool back;
      if (!consider(fan, &back)) continue;
      if (back && cull_back) continue;
      if (opt.cull_view && outside(fan)) continue;
      out->corners.push_back({ids[0], ids[k], ids[k + 1]});
      out->source.push_back(uint32_t(t));
    }
  }
  *counts += c;
}

}  // namespace zs
