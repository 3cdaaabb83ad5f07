// The surface renderer's per-triangle set-up (render/surfaces/triangle_shade.h) and
// the batch kernel that evaluates it (render/surfaces/shade_batch.h), against the
// closed form computed from scratch per pixel: the ray's hit with the
// triangle (Möller–Trumbore), its view depth, the barycentric (Phong)
// normal and the face normal, both turned to the eye.
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/surfaces/shade_batch.h"
#include "render/surfaces/triangle_shade.h"

namespace zs {
namespace {

struct Expected {
  bool hit = false;
  glm::dvec3 p, g, n;
  double depth = 0;
};

// Pixel (X, Y)'s ray against triangle t, from scratch.
Expected closed_form(const TriangleMesh& m, uint32_t t, const View& v, double X, double Y) {
  glm::dvec3 o, d;
  v.ray(X, Y, &o, &d);
  const auto& tri = m.tris[t];
  const glm::dvec3 A = m.points[tri[0]], B = m.points[tri[1]], C = m.points[tri[2]];
  const glm::dvec3 e1 = B - A, e2 = C - A, pv = glm::cross(d, e2);
  const double det = glm::dot(e1, pv);
  Expected e;
  if (std::abs(det) < 1e-12) return e;
  const glm::dvec3 tv = o - A, qv = glm::cross(tv, e1);
  const double u = glm::dot(tv, pv) / det, w = glm::dot(d, qv) / det, s = glm::dot(e2, qv) / det;
  // Well inside, so rounding cannot put the pixel on the other side of an edge.
  if (u < 0.02 || w < 0.02 || u + w > 0.98 || s <= 0) return e;
  e.hit = true;
  e.p = o + s * d;
  e.depth = v.depth(e.p);
  e.g = glm::normalize(glm::cross(e1, e2));
  const double fl = glm::dot(e.g, d) > 0 ? -1.0 : 1.0;
  e.g *= fl;
  e.n = fl * glm::normalize((1 - u - w) * m.normals[tri[0]] + u * m.normals[tri[1]] + w * m.normals[tri[2]]);
  return e;
}

void check_view(const Camera& cam, const glm::dvec3& offset, double scale, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  TriangleMesh m;
  const int kTris = 40;
  for (int t = 0; t < kTris; ++t) {
    const glm::dvec3 c(U(rng), U(rng), U(rng));
    for (int k = 0; k < 3; ++k) {
      m.points.push_back(offset + scale * (c + 0.6 * glm::dvec3(U(rng), U(rng), U(rng))));
      m.normals.push_back(glm::normalize(glm::dvec3(U(rng), U(rng), U(rng)) + glm::dvec3(0, 0, 0.2)));
    }
    m.tris.push_back({uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2)});
    m.surface.push_back(0);
  }
  const uint32_t W = 48, H = 40;
  const View v(cam, W, H);
  int checked = 0;
  for (ShadingModel model : {ShadingModel::Phong, ShadingModel::Flat}) {
    for (uint32_t t = 0; t < m.num_tris(); ++t) {
      const TriangleShade ts = triangle_shade(m, t, v, model, glm::dvec3(0.5, 0.25, 1.0));
      EXPECT_EQ(ts.color[1], 0.25f);
      for (uint32_t y = 0; y < H; ++y) {
        ShadeBatch b;
        b.points = true;
        b.Y = double(y);
        std::vector<Expected> want;
        for (uint32_t x = 0; x < W && b.n < kShadeBatch; ++x) {
          const Expected e = closed_form(m, t, v, x, y);
          if (!e.hit) continue;
          b.X[b.n] = x, b.zbuf[b.n] = NAN, b.id[b.n] = 0, b.tri[b.n] = 0;
          ++b.n;
          want.push_back(e);
        }
        if (b.n == 0) continue;
        surface_hits(v, &ts, b);
        const double tol = 1e-9 * scale + 1e-13 * glm::length(offset);
        for (int i = 0; i < b.n; ++i) {
          const Expected& e = want[size_t(i)];
          EXPECT_NEAR(b.depth[i], e.depth, tol);
          EXPECT_NEAR(glm::length(glm::dvec3(b.px[i], b.py[i], b.pz[i]) - e.p), 0.0, tol);
          const glm::dvec3 n = model == ShadingModel::Phong ? e.n : e.g;
          EXPECT_NEAR(glm::length(glm::dvec3(ts.g[0], ts.g[1], ts.g[2]) - e.g), 0.0, 1e-9);
          // Unit vectors are floats (shade_batch.h).
          EXPECT_NEAR(glm::length(glm::dvec3(b.sx[i], b.sy[i], b.sz[i]) - n), 0.0, 1e-6);
          glm::dvec3 o, d;
          v.ray(double(b.X[i]), double(y), &o, &d);
          EXPECT_NEAR(glm::length(glm::dvec3(b.vx[i], b.vy[i], b.vz[i]) + d), 0.0, 1e-6);
          EXPECT_EQ(b.base[2][i], 1.0f);
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 600);  // the triangles cover a good part of the image
}

TEST(TriangleShade, HitDepthAndNormalsMatchClosedFormPerspective) {
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {0.7, 1.1, 4.0}, cam.target = {0, 0, 0}, cam.fov_y = 45;
  check_view(cam, glm::dvec3(0), 1.0, 1);
}

TEST(TriangleShade, HitDepthAndNormalsMatchClosedFormOrthographic) {
  Camera cam;
  cam.projection = Projection::Orthographic;
  cam.eye = {-2.0, 1.5, 3.0}, cam.target = {0, 0, 0}, cam.height = 3.5;
  check_view(cam, glm::dvec3(0), 1.0, 2);
}

TEST(TriangleShade, FarFromTheOriginAndSmall) {
  // Coordinates 1e5 from the origin, triangles of size 1e-2: the set-up is
  // taken relative to the triangle and the eye, so the error stays at the
  // coordinates' own rounding.
  const glm::dvec3 off(1e5, -2e5, 3e4);
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = off + glm::dvec3(0.007, 0.011, 0.04), cam.target = off, cam.fov_y = 45;
  check_view(cam, off, 0.01, 3);
}

// depth_range (the empty-tile early out's depth bounds): the least and
// greatest depth of the covered pixels only, across signs and zeros, and NaN
// when a covered depth is NaN.
TEST(TriangleShade, DepthRangeOfCoveredPixels) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    ShadeBatch b;
    b.n = 1 + int(rng() % kShadeBatch);
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < b.n; ++i) {
      const int kind = int(rng() % 6);
      b.depth[i] = kind == 0 ? 0.0 : kind == 1 ? -0.0 : kind == 2 ? 1e300 * U(rng) : U(rng) * std::exp2(int(rng() % 40) - 20);
      const bool covered = rng() % 4 != 0;
      b.id[i] = covered ? uint32_t(i) : kNoShade;
      if (!covered) b.depth[i] = (rng() % 2 ? -1 : 1) * 1e308;  // must not count
      if (covered) lo = std::min(lo, b.depth[i]), hi = std::max(hi, b.depth[i]);
    }
    double got_lo, got_hi;
    depth_range(b, &got_lo, &got_hi);
    if (lo > hi) {  // nothing covered
      EXPECT_EQ(got_lo, INFINITY);
      EXPECT_EQ(got_hi, -INFINITY);
      continue;
    }
    EXPECT_EQ(got_lo, lo);  // ±0 compare equal, either may come back
    EXPECT_EQ(got_hi, hi);
    b.id[0] = 0, b.depth[0] = NAN;
    depth_range(b, &got_lo, &got_hi);
    EXPECT_FALSE(got_lo <= got_hi);
  }
}

}  // namespace
}  // namespace zs
