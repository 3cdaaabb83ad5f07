// Near-plane triangle clip: the four in/out cases, cut points on the plane,
// attributes, winding and area.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "raster/triangle_clip.h"

namespace zs {
namespace {

// Attributes affine in position, so their cut values are known exactly.
void set_attrs(ClipVertex* v) {
  for (int k = 0; k < kClipMaxAttrs; ++k) v->attr[k] = float(k + 1) * float(v->x) - 2.0f * float(v->y) + float(k) * float(v->z) + 0.5f;
}

ClipVertex vert(double x, double y, double z) {
  ClipVertex v{x, y, z, {}};
  set_attrs(&v);
  return v;
}

// Vector area (half the cross product sum) of a planar polygon.
void vector_area(const ClipVertex* v, int n, double a[3]) {
  a[0] = a[1] = a[2] = 0;
  for (int k = 1; k + 1 < n; ++k) {
    const double ux = v[k].x - v[0].x, uy = v[k].y - v[0].y, uz = v[k].z - v[0].z;
    const double wx = v[k + 1].x - v[0].x, wy = v[k + 1].y - v[0].y, wz = v[k + 1].z - v[0].z;
    a[0] += 0.5 * (uy * wz - uz * wy);
    a[1] += 0.5 * (uz * wx - ux * wz);
    a[2] += 0.5 * (ux * wy - uy * wx);
  }
}

TEST(TriangleClip, AllInAllOut) {
  const ClipVertex in[3] = {vert(0, 0, 2), vert(1, 0, 3), vert(0, 1, 1)};
  ClipPolygon poly;
  EXPECT_EQ(clip_triangle_near(in, 3, 1.0, &poly), 3);  // z = z_near counts as inside
  for (int k = 0; k < 3; ++k) EXPECT_EQ(poly.v[k].z, in[k].z);
  EXPECT_EQ(clip_triangle_near(in, 3, 3.5, &poly), 0);
  EXPECT_EQ(poly.n, 0);
  ClipVertex tri[2][3];
  EXPECT_EQ(fan_triangles(poly, tri), 0);
  // Touching the plane from behind at one vertex or along an edge: nothing.
  const ClipVertex touch[3] = {vert(0, 0, 1), vert(1, 0, 0.5), vert(0, 1, 0.2)};
  EXPECT_EQ(clip_triangle_near(touch, 3, 1.0, &poly), 0);
  const ClipVertex edge[3] = {vert(0, 0, 1), vert(1, 0, 1), vert(0, 1, 0.2)};
  EXPECT_EQ(clip_triangle_near(edge, 3, 1.0, &poly), 0);
}

// Random triangles with each count of inside vertices: the cut vertices lie on
// the plane, attributes are the affine function there, the winding (vector
// area direction) is kept, and the area matches the closed form.
TEST(TriangleClip, OneAndTwoInsideAgainstClosedForm) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(-1, 1);
  const double zn = 1.0;
  int cases[4] = {0, 0, 0, 0};
  for (int rep = 0; rep < 2000; ++rep) {
    ClipVertex in[3];
    for (ClipVertex& v : in) v = vert(3 * U(rng), 3 * U(rng), zn + 2 * U(rng));
    int n_in = 0;
    for (const ClipVertex& v : in) n_in += v.z >= zn;
    ++cases[n_in];
    ClipPolygon poly;
    const int n = clip_triangle_near(in, kClipMaxAttrs, zn, &poly);
    ASSERT_EQ(n, n_in == 0 ? 0 : n_in == 3 ? 3 : n_in == 1 ? 3 : 4);
    if (n == 0) continue;
    double full[3], part[3];
    vector_area(in, 3, full);
    vector_area(poly.v, n, part);
    const double full_len = std::sqrt(full[0] * full[0] + full[1] * full[1] + full[2] * full[2]);
    const double part_len = std::sqrt(part[0] * part[0] + part[1] * part[1] + part[2] * part[2]);
    // Same orientation: the clipped polygon is part of the same plane, same side.
    EXPECT_GT(full[0] * part[0] + full[1] * part[1] + full[2] * part[2], 0.999999 * full_len * part_len);
    // Closed form: one inside vertex i keeps the triangle scaled by u·v along
    // its two edges; one outside vertex o removes the triangle scaled so.
    double want = full_len;
    if (n_in == 1 || n_in == 2) {
      int odd = 0;
      for (int k = 0; k < 3; ++k)
        if ((in[k].z >= zn) == (n_in == 1)) odd = k;
      const ClipVertex& o = in[odd];
      const double u = (o.z - zn) / (o.z - in[(odd + 1) % 3].z), v = (o.z - zn) / (o.z - in[(odd + 2) % 3].z);
      want = n_in == 1 ? full_len * u * v : full_len * (1 - u * v);
    }
    EXPECT_NEAR(part_len, want, 1e-9 * (1 + full_len));
    for (int k = 0; k < n; ++k) {
      const ClipVertex& v = poly.v[k];
      EXPECT_GE(v.z, zn);
      bool original = false;
      for (const ClipVertex& w : in) original |= (w.x == v.x && w.y == v.y && w.z == v.z);
      if (original) continue;
      EXPECT_EQ(v.z, zn);  // exactly on the plane
      ClipVertex want_attrs = v;
      set_attrs(&want_attrs);
      for (int a = 0; a < kClipMaxAttrs; ++a)
        EXPECT_NEAR(v.attr[a], want_attrs.attr[a], 2e-5f * (1 + std::fabs(want_attrs.attr[a]))) << a;
    }
    ClipVertex tri[2][3];
    const int nt = fan_triangles(poly, tri);
    ASSERT_EQ(nt, n - 2);
    double sum = 0;
    for (int t = 0; t < nt; ++t) {
      double a[3];
      vector_area(tri[t], 3, a);
      EXPECT_GE(a[0] * full[0] + a[1] * full[1] + a[2] * full[2], 0);  // winding kept
      sum += std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    }
    EXPECT_NEAR(sum, part_len, 1e-9 * (1 + full_len));
  }
  for (int c = 0; c < 4; ++c) EXPECT_GT(cases[c], 50) << c;
}

TEST(TriangleClip, SharedEdgeIsCutAtTheSamePoint) {
  // Two triangles sharing edge A–B, walked in opposite directions.
  const ClipVertex A = vert(0.3, -0.7, 2.5), B = vert(-1.1, 0.9, 0.2), C = vert(2, 2, 3), D = vert(-2, -2, 0.1);
  const ClipVertex t1[3] = {A, B, C}, t2[3] = {B, A, D};
  ClipPolygon p1, p2;
  ASSERT_GT(clip_triangle_near(t1, 2, 1.0, &p1), 0);
  ASSERT_GT(clip_triangle_near(t2, 2, 1.0, &p2), 0);
  auto find_cut = [](const ClipPolygon& p, double* x, double* y) {
    // The cut point of A–B: on the plane and on the line A–B (y linear in x there).
    for (int k = 0; k < p.n; ++k)
      if (p.v[k].z == 1.0 && std::fabs((p.v[k].x - 0.3) * 1.6 - (p.v[k].y + 0.7) * -1.4) < 1e-12) {
        *x = p.v[k].x, *y = p.v[k].y;
        return true;
      }
    return false;
  };
  double x1, y1, x2, y2;
  ASSERT_TRUE(find_cut(p1, &x1, &y1));
  ASSERT_TRUE(find_cut(p2, &x2, &y2));
  EXPECT_EQ(x1, x2);  // bit for bit
  EXPECT_EQ(y1, y2);
}

}  // namespace
}  // namespace zs
