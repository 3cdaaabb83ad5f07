// The raster core's z-buffer (src/raster/zbuffer_tile.h) on projected
// triangles: nearest depth and id against closed-form ray–triangle hits, and
// the depth-only kernel of the shadow maps against it, bit for bit.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "lighting/triangle_projection.h"
#include "raster/depth_buffer.h"
#include "raster/zbuffer_tile.h"

namespace zs {
namespace {

// Möller–Trumbore in double: the ray parameter, or NaN on a miss; `margin`
// gets the smallest barycentric (how far inside).
double ray_tri(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
               const glm::dvec3& c, double* margin) {
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (det == 0) return NAN;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) / det;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det, t = glm::dot(e2, q) / det;
  *margin = std::min({u, v, 1 - u - v});
  return *margin >= 0 && t > 0 ? t : NAN;
}

// The raster core's z-buffer (span scan, nearest depth, ties to the smaller
// id) against brute-force ray casting of every triangle, both projections.
TEST(Surfaces, ZBufferDepthMatchesClosedFormRayTriangleHits) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  TriangleMesh m;
  for (int t = 0; t < 40; ++t) {
    const glm::dvec3 c(U(rng), U(rng), U(rng));
    const uint32_t base = uint32_t(m.points.size());
    for (int k = 0; k < 3; ++k) m.points.push_back(c + 0.6 * glm::dvec3(U(rng), U(rng), U(rng)));
    m.tris.push_back({base, base + 1, base + 2});
  }
  m.surface.assign(m.tris.size(), 0);
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    Camera cam;
    cam.projection = proj;
    cam.eye = {0.3, 0.4, 5};
    cam.target = {0, 0, 0};
    cam.height = 3.4;
    cam.fov_y = 36;
    const uint32_t W = 96, H = 80;
    const View view(cam, W, H);
    ProjectedTriangles pt;
    ProjectCounts pc;
    project_triangles(m, view, {false, true, 1e-6}, &pt, &pc);
    DepthBuffer db;
    db.reset(W, H);
    std::vector<uint32_t> ids(pt.corners.size());
    for (uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
    ZBufferScratch scratch;
    ZBufferCounts zc;
    zbuffer_triangles(pt.verts, pt.corners, ids.data(), ids.size(), pt.perspective, {0, 0, int(W), int(H)}, db,
                      scratch, &zc);
    // The depth-only kernel (shadow maps) keeps the same front depths, bit
    // for bit, over tiles of any size, and scans the same fragments.
    for (int ts : {16, 33, 96}) {
      std::vector<double> only(size_t(W) * H, INFINITY);
      ZBufferCounts oc;
      for (int y0 = 0; y0 < int(H); y0 += ts)
        for (int x0 = 0; x0 < int(W); x0 += ts) {
          const Viewport vp{x0, y0, std::min(x0 + ts, int(W)), std::min(y0 + ts, int(H))};
          std::vector<double> tile(size_t(vp.x1 - vp.x0) * (vp.y1 - vp.y0), INFINITY);
          zbuffer_depths(pt.verts, pt.corners, ids.data(), ids.size(), pt.perspective, vp, tile.data(), scratch, &oc);
          for (int y = vp.y0; y < vp.y1; ++y)
            for (int x = vp.x0; x < vp.x1; ++x)
              only[size_t(y) * W + x] = tile[size_t(y - vp.y0) * (vp.x1 - vp.x0) + (x - vp.x0)];
        }
      EXPECT_EQ(oc.fragments, zc.fragments);
      for (size_t p = 0; p < only.size(); ++p) ASSERT_EQ(only[p], db.depth(p)) << "tile " << ts << " pixel " << p;
    }
    uint32_t checked = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        glm::dvec3 o, d;
        view.ray(x, y, &o, &d);
        double best = INFINITY, second = INFINITY, best_margin = 0;
        uint32_t best_t = kNoId;
        bool near_edge = false;
        for (size_t t = 0; t < m.num_tris(); ++t) {
          double margin;
          const double h = ray_tri(o, d, m.points[m.tris[t][0]], m.points[m.tris[t][1]], m.points[m.tris[t][2]], &margin);
          near_edge |= std::abs(margin) < 1e-9;
          if (!(h == h)) continue;
          if (h < best) {
            second = best;
            best = h;
            best_t = uint32_t(t);
            best_margin = margin;
          } else {
            second = std::min(second, h);
          }
        }
        if (near_edge || second - best < 1e-9) continue;  // ties: either answer is right
        const size_t p = size_t(y) * W + x;
        const uint32_t got = db.id(p) == kNoId ? kNoId : pt.source[db.id(p)];
        ASSERT_EQ(got, best_t) << x << "," << y;
        if (best_t != kNoId) {
          const double depth = glm::dot(o + d * best - view.eye(), view.forward());
          EXPECT_NEAR(db.depth(p), depth, 1e-12 * (1 + std::abs(depth))) << x << "," << y;
          ++checked;
        }
        (void)best_margin;
      }
    EXPECT_GT(checked, W * H / 8);
  }
}

}  // namespace
}  // namespace zs
