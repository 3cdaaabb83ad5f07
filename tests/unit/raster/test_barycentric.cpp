// Barycentric weights: the vertices' own weights, and perspective-correct
// interpolation equal to the pixel ray's intersection with the triangle's plane.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "raster/barycentric.h"

namespace zs {
namespace {

struct P3 {
  double x, y, z;
};
P3 sub(P3 a, P3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
P3 cross(P3 a, P3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(P3 a, P3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Camera-space point to screen (focal f pixels, centre (ox, oy)).
ScreenVertex project(P3 p, bool persp, double f, double ox, double oy, uint32_t id) {
  const double a = persp ? p.x / p.z : p.x, b = persp ? p.y / p.z : p.y;
  return {f * a + ox, oy - f * b, p.z, 0.0, id};
}

TEST(Barycentric, VerticesGetTheirOwnWeights) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int persp = 0; persp < 2; ++persp)
    for (int rep = 0; rep < 200; ++rep) {
      P3 p[3];
      ScreenVertex v[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = {U(rng) * 3, U(rng) * 3, 4 + 3 * U(rng)};
        v[k] = project(p[k], persp, 200, 100, 80, uint32_t(k));
      }
      Barycentric b;
      ASSERT_TRUE(setup_barycentric(v, persp, &b));
      for (int k = 0; k < 3; ++k) {
        double w[3];
        b.weights(v[k].x, v[k].y, w);
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(w[j], j == k ? 1.0 : 0.0, 1e-12) << k << " " << j;
        EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-15);  // w0 = 1 − w1 − w2: one rounding
      }
      double w[3];
      b.weights(v[0].x, v[0].y, w);
      EXPECT_EQ(w[0], 1.0);  // exact at vertex 0
    }
}

TEST(Barycentric, PerspectiveInterpolationHitsTheTrianglePlane) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> U(-1, 1);
  const double f = 250, ox = 160, oy = 120;
  int checked = 0;
  for (int persp = 0; persp < 2; ++persp)
    for (int rep = 0; rep < 300; ++rep) {
      P3 p[3];
      ScreenVertex v[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = {U(rng) * 4, U(rng) * 4, 6 + 5 * U(rng)};
        v[k] = project(p[k], persp, f, ox, oy, uint32_t(k));
      }
      Barycentric b;
      ASSERT_TRUE(setup_barycentric(v, persp, &b));
      const P3 n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
      for (int s = 0; s < 20; ++s) {
        // A pixel centre inside the screen triangle (random screen weights).
        double l[3] = {std::fabs(U(rng)), std::fabs(U(rng)), std::fabs(U(rng))};
        const double sum = l[0] + l[1] + l[2];
        const double X = std::round((l[0] * v[0].x + l[1] * v[1].x + l[2] * v[2].x) / sum);
        const double Y = std::round((l[0] * v[0].y + l[1] * v[1].y + l[2] * v[2].y) / sum);
        double w[3];
        b.weights(X, Y, w);
        const P3 q = {w[0] * p[0].x + w[1] * p[1].x + w[2] * p[2].x, w[0] * p[0].y + w[1] * p[1].y + w[2] * p[2].y,
                      w[0] * p[0].z + w[1] * p[1].z + w[2] * p[2].z};
        // Closed form: the pixel's ray against the plane n·(x − p0) = 0.
        const double a = (X - ox) / f, bb = (oy - Y) / f;
        P3 hit;
        if (persp) {
          const P3 d = {a, bb, 1};
          const double t = dot(n, p[0]) / dot(n, d);
          hit = {t * a, t * bb, t};
        } else {
          const double z = p[0].z - (n.x * (a - p[0].x) + n.y * (bb - p[0].y)) / n.z;
          hit = {a, bb, z};
        }
        // Relative, times the ray/plane conditioning |n||d|/|n·d| (grazing
        // planes amplify rounding; the rounded pixel may lie just outside).
        const P3 d = persp ? P3{a, bb, 1} : P3{0, 0, 1};
        const double cond = std::sqrt(dot(n, n) * dot(d, d)) / std::fabs(dot(n, d));
        const double tol = 1e-12 * (std::sqrt(dot(hit, hit)) + 1) * cond;
        EXPECT_NEAR(q.x, hit.x, tol);
        EXPECT_NEAR(q.y, hit.y, tol);
        EXPECT_NEAR(q.z, hit.z, tol);
        ++checked;
      }
    }
  EXPECT_EQ(checked, 2 * 300 * 20);
}

TEST(Barycentric, PerspectiveDiffersFromLinearAndDegenerateIsRejected) {
  // A strongly slanted triangle: the perspective midpoint weight is not 1/2.
  ScreenVertex v[3] = {{0, 0, 1, 0, 0}, {100, 0, 9, 0, 1}, {0, 100, 1, 0, 2}};
  Barycentric b;
  ASSERT_TRUE(setup_barycentric(v, true, &b));
  double w[3];
  b.weights(50, 0, w);
  // Along edge 0–1, w1 = (λ/z1)/((1−λ)/z0 + λ/z1) with λ = 1/2: 0.1.
  EXPECT_NEAR(w[1], 0.1, 1e-15);
  EXPECT_NEAR(w[0], 0.9, 1e-15);
  EXPECT_EQ(w[2], 0.0);
  ASSERT_TRUE(setup_barycentric(v, false, &b));
  b.weights(50, 0, w);
  EXPECT_EQ(w[1], 0.5);
  ScreenVertex flat[3] = {{0, 0, 1, 0, 0}, {1, 1, 2, 0, 1}, {2, 2, 3, 0, 2}};
  EXPECT_FALSE(setup_barycentric(flat, true, &b));
  ScreenVertex behind[3] = {{0, 0, 1, 0, 0}, {10, 0, -1, 0, 1}, {0, 10, 1, 0, 2}};
  EXPECT_FALSE(setup_barycentric(behind, true, &b));
  EXPECT_TRUE(setup_barycentric(behind, false, &b));
}

}  // namespace
}  // namespace zs
