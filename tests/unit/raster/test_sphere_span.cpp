// Sphere footprints: scan_sphere against brute force, sphere_hit against an
// independent long-double ray tracer, special placements, ellipse areas.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "raster/sphere_span.h"

namespace zs {
namespace {

using LD = long double;

struct Scene {
  CameraPlane cam;
  int W, H;
};

// Independent reference: world-style ray (origin, unit direction), solved in
// long double as |o + s·u − c|² = r², depth = s·u_z.
struct RefHit {
  bool hit;
  LD t_in, t_out, sq, uz, scale;  // sq: sqrt of the discriminant (world units)
  LD disc;
};
RefHit ref_hit(const CameraPlane& cam, int i, int j, LD cx, LD cy, LD cz, LD r) {
  const LD a = (LD(i) - cam.ox) / cam.sx, b = (LD(cam.oy) - j) / cam.sy;
  LD o[3] = {0, 0, 0}, u[3] = {0, 0, 1};
  if (cam.perspective) {
    const LD n = std::sqrt(a * a + b * b + 1);
    u[0] = a / n, u[1] = b / n, u[2] = 1 / n;
  } else {
    o[0] = a, o[1] = b;
  }
  const LD oc[3] = {o[0] - cx, o[1] - cy, o[2] - cz};
  const LD B = u[0] * oc[0] + u[1] * oc[1] + u[2] * oc[2];
  const LD C = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - r * r;
  RefHit h{};
  h.disc = B * B - C;
  h.uz = u[2];
  h.scale = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] + o[0] * o[0] + o[1] * o[1] + r * r;
  if (h.disc < 0) return h;
  h.sq = std::sqrt(h.disc);
  h.t_in = (-B - h.sq) * u[2];
  h.t_out = (-B + h.sq) * u[2];
  h.hit = h.t_out > 0;
  return h;
}

Scene random_scene(std::mt19937& rng, bool perspective) {
  std::uniform_real_distribution<double> U(0, 1);
  Scene s;
  s.W = 96 + int(U(rng) * 96), s.H = 64 + int(U(rng) * 96);
  s.cam.perspective = perspective;
  const double f = perspective ? 60 + 300 * U(rng) : 4 + 40 * U(rng);
  s.cam.sx = f * (0.7 + 0.6 * U(rng));
  s.cam.sy = f;
  s.cam.ox = s.W * (0.2 + 0.6 * U(rng));
  s.cam.oy = s.H * (0.2 + 0.6 * U(rng));
  return s;
}

struct Ball {
  double x, y, z, r;
};

// Placements covering every case of the footprint (kind 0..7).
Ball random_ball(std::mt19937& rng, const Scene& sc, int kind) {
  std::uniform_real_distribution<double> U(0, 1);
  auto S = [&](double lo, double hi) { return lo + (hi - lo) * U(rng); };
  const double span = sc.cam.perspective ? 1.0 : sc.W / sc.cam.sx;  // half-width of the view in camera-plane units
  Ball b{};
  switch (kind) {
    case 0:  // in front, moderate
      b.z = S(1, 30);
      if (sc.cam.perspective) b.x = S(-0.6, 0.6) * b.z, b.y = S(-0.6, 0.6) * b.z, b.r = S(0.02, 0.4) * b.z;
      else b.x = S(-span, span), b.y = S(-span, span), b.r = S(0.02, 0.4) * span;
      break;
    case 1: {  // sub-pixel or a few pixels
      b.z = S(1, 30);
      const double px = S(0.1, 2.0);
      b.x = S(-0.5, 0.5) * (sc.cam.perspective ? b.z : span), b.y = S(-0.5, 0.5) * (sc.cam.perspective ? b.z : span);
      b.r = sc.cam.perspective ? px * b.z / sc.cam.sy : px / sc.cam.sy;
      break;
    }
    case 2:  // beside the eye, cut by the eye plane
      b.r = S(0.5, 3), b.z = S(-b.r, b.r), b.x = S(-3, 3) * b.r, b.y = S(-3, 3) * b.r;
      break;
    case 3:  // containing the eye
      b.r = S(0.5, 5), b.x = S(-0.5, 0.5) * b.r, b.y = S(-0.5, 0.5) * b.r, b.z = S(-0.5, 0.5) * b.r;
      break;
    case 4:  // behind the eye
      b.r = S(0.1, 3), b.z = -b.r - S(0.01, 5), b.x = S(-2, 2), b.y = S(-2, 2);
      break;
    case 5:  // huge, covering the screen
      b.z = S(2, 10), b.r = b.z * S(0.9, 0.999), b.x = S(-0.2, 0.2), b.y = S(-0.2, 0.2);
      break;
    case 6:  // nearly touching the eye plane from in front (parabola-like silhouette)
      b.r = S(0.5, 2), b.z = b.r * (1 + S(-1e-3, 1e-3)), b.x = S(-1, 1), b.y = S(-1, 1);
      break;
    default:  // off-axis in front, partly off-screen
      b.z = S(1, 8), b.x = S(-2, 2) * b.z, b.y = S(-2, 2) * b.z, b.r = S(0.1, 0.9) * b.z;
      if (!sc.cam.perspective) b.x = S(-1.2, 1.2) * span, b.y = S(-1.2, 1.2) * span, b.r = S(0.05, 0.5) * span;
      break;
  }
  return b;
}

Viewport random_viewport(std::mt19937& rng, const Scene& sc) {
  std::uniform_int_distribution<int> coin(0, 2);
  if (coin(rng) == 0) return {0, 0, sc.W, sc.H};
  std::uniform_int_distribution<int> X(0, sc.W - 1), Y(0, sc.H - 1);
  int a = X(rng), b = X(rng), c = Y(rng), d = Y(rng);
  return {std::min(a, b), std::min(c, d), std::max(a, b) + 1, std::max(c, d) + 1};
}

// scan_sphere's runs against {(i, j) in vp : sphere_hit}.
void expect_scan_matches_brute(const SphereSetup& s, const Viewport& vp, uint64_t* pixels) {
  FaceSpans spans;
  ScanCounters c;
  scan_sphere(s, vp, spans, c);
  std::vector<char> got(size_t(vp.x1 - vp.x0) * size_t(vp.y1 - vp.y0), 0);
  int last_y = vp.y0 - 1;
  for (const RowSpan& r : spans.rows) {
    ASSERT_GT(r.y, last_y);
    last_y = r.y;
    ASSERT_LT(r.y, vp.y1);
    ASSERT_LE(vp.x0, r.x0);
    ASSERT_LE(r.x0, r.x1);
    ASSERT_LT(r.x1, vp.x1);
    for (int x = r.x0; x <= r.x1; ++x) got[size_t(r.y - vp.y0) * size_t(vp.x1 - vp.x0) + size_t(x - vp.x0)] = 1;
  }
  uint64_t n = 0;
  for (int j = vp.y0; j < vp.y1; ++j)
    for (int i = vp.x0; i < vp.x1; ++i) {
      SphereHit h;
      const bool want = sphere_hit(s, i, j, &h);
      n += want;
      ASSERT_EQ(want, bool(got[size_t(j - vp.y0) * size_t(vp.x1 - vp.x0) + size_t(i - vp.x0)]))
          << "pixel " << i << "," << j << " sphere " << s.cx << "," << s.cy << "," << s.cz << " r " << s.r
          << (s.cam.perspective ? " persp" : " ortho");
    }
  EXPECT_EQ(n, spans.pixels());
  EXPECT_EQ(c.pixel_hits, n);
  EXPECT_LE(c.pixel_misses, c.pixel_tests);
  int i0, i1, j0, j1;
  const bool any = sphere_pixel_range(s, vp, &i0, &i1, &j0, &j1);
  // The analytic row ends are (nearly) right: about two tests per row end,
  // one per row of the box that misses the viewport's columns.
  if (any) EXPECT_LE(c.pixel_tests, 4 * spans.size() + uint64_t(j1 - j0 + 1) + 2);
  else EXPECT_EQ(c.pixel_tests, 0u);
  if (n > 0) {
    ASSERT_TRUE(any);
    for (const RowSpan& r : spans.rows) {
      EXPECT_GE(r.y, j0);
      EXPECT_LE(r.y, j1);
      EXPECT_GE(r.x0, i0);
      EXPECT_LE(r.x1, i1);
    }
  }
  *pixels += n;
}

TEST(SphereSpan, ScanEqualsBruteForce) {
  std::mt19937 rng(12345);
  uint64_t pixels = 0, spheres = 0;
  for (int proj = 0; proj < 2; ++proj)
    for (int rep = 0; rep < 12; ++rep) {
      const Scene sc = random_scene(rng, proj == 1);
      for (int kind = 0; kind < 8; ++kind)
        for (int k = 0; k < 6; ++k) {
          const Ball b = random_ball(rng, sc, kind);
          const SphereSetup s = setup_sphere(sc.cam, b.x, b.y, b.z, b.r);
          expect_scan_matches_brute(s, random_viewport(rng, sc), &pixels);
          ++spheres;
          if (HasFatalFailure()) return;
        }
    }
  EXPECT_GT(pixels, 100000u);  // the cases are not all empty
  EXPECT_EQ(spheres, 2u * 12 * 8 * 6);
}

// The block depth bound: no hit in a block is nearer, and it is tighter than
// the sphere's nearest depth for blocks away from that point.
TEST(SphereSpan, DepthBoundHoldsForEveryHitOfItsBlock) {
  std::mt19937 rng(4242);
  uint64_t hits = 0, blocks = 0, tighter = 0;
  for (int proj = 0; proj < 2; ++proj)
    for (int rep = 0; rep < 12; ++rep) {
      const Scene sc = random_scene(rng, proj == 1);
      for (int kind = 0; kind < 8; ++kind)
        for (int k = 0; k < 6; ++k) {
          const Ball b = random_ball(rng, sc, kind);
          const SphereSetup s = setup_sphere(sc.cam, b.x, b.y, b.z, b.r);
          const double zn = b.z - b.r;
          for (int q = 0; q < 8; ++q) {
            const int size = 1 + int(rng() % 16);
            const int x0 = int(rng() % uint32_t(sc.W)), y0 = int(rng() % uint32_t(sc.H));
            const int x1 = std::min(sc.W - 1, x0 + size - 1), y1 = std::min(sc.H - 1, y0 + size - 1);
            const double bound = sphere_depth_bound(s, x0, x1, y0, y1);
            if (!(zn > 0)) {
              EXPECT_EQ(bound, -INFINITY);
              continue;
            }
            ++blocks;
            EXPECT_GE(bound, zn - 1e-6 * (std::fabs(b.z) + b.r));
            bool any = false;
            for (int j = y0; j <= y1; ++j)
              for (int i = x0; i <= x1; ++i) {
                SphereHit h;
                if (!sphere_hit(s, i, j, &h)) continue;
                any = true;
                ++hits;
                EXPECT_GE(h.t, bound) << "pixel " << i << "," << j << " block " << x0 << ".." << x1 << " x " << y0
                                      << ".." << y1;
              }
            tighter += any && bound > zn + 1e-3 * b.r;
            if (HasFatalFailure()) return;
          }
        }
    }
  EXPECT_GT(hits, 10000u);
  EXPECT_GT(tighter, blocks / 20);
}

// Depths and hit classification against the long-double ray tracer.
TEST(SphereSpan, HitMatchesLongDoubleRayTracer) {
  std::mt19937 rng(777);
  uint64_t compared = 0, tight = 0;
  for (int proj = 0; proj < 2; ++proj)
    for (int rep = 0; rep < 6; ++rep) {
      const Scene sc = random_scene(rng, proj == 1);
      for (int kind = 0; kind < 8; ++kind)
        for (int k = 0; k < 4; ++k) {
          const Ball b = random_ball(rng, sc, kind);
          const SphereSetup s = setup_sphere(sc.cam, b.x, b.y, b.z, b.r);
          for (int j = 0; j < sc.H; j += 2)
            for (int i = 0; i < sc.W; i += 2) {
              SphereHit h;
              const bool got = sphere_hit(s, i, j, &h);
              const RefHit ref = ref_hit(sc.cam, i, j, b.x, b.y, b.z, b.r);
              const LD r = b.r;
              // Classification where it is not within rounding of the silhouette or the eye plane.
              const bool clear = std::fabs(ref.disc) > 1e-9L * r * r &&
                                 (!ref.hit || ref.t_out > 1e-9L * (std::fabs(ref.t_in) + r));
              if (clear) ASSERT_EQ(got, ref.hit) << i << "," << j << " kind " << kind;
              if (!got || !ref.hit) continue;
              // Depth error: relative, plus the silhouette's amplification of
              // the discriminant's rounding (~ eps·scale/sqrt(disc)).
              const LD cond = 1e-13L * ref.scale * ref.uz / std::max(ref.sq, 1e-30L);
              const LD tol_in = 1e-12L * (std::fabs(ref.t_in) + r) + cond;
              const LD tol_out = 1e-12L * (std::fabs(ref.t_out) + r) + cond;
              EXPECT_NEAR(LD(h.t_in), ref.t_in, tol_in) << i << "," << j << " kind " << kind;
              EXPECT_NEAR(LD(h.t_out), ref.t_out, tol_out) << i << "," << j << " kind " << kind;
              EXPECT_LE(h.t_in, h.t_out);
              EXPECT_GT(h.t, 0);
              EXPECT_EQ(h.t, h.inside ? h.t_out : h.t_in);
              if (std::fabs(ref.t_in) > tol_in) EXPECT_EQ(h.inside, ref.t_in <= 0);
              ++compared;
              // Well inside the silhouette the depths are exact to ~1e-12 relative.
              if (ref.sq > 0.5L * r) {
                EXPECT_NEAR(LD(h.t), h.inside ? ref.t_out : ref.t_in, 1e-12L * (std::fabs(LD(h.t)) + r));
                ++tight;
              }
              if (HasFailure()) return;
            }
        }
    }
  EXPECT_GT(compared, 50000u);
  EXPECT_GT(tight, 20000u);
}

TEST(SphereSpan, EyeInsideCoversEveryPixelWithExitDepth) {
  CameraPlane cam{true, 120, 120, 40.5, 30.5};
  const Viewport vp{0, 0, 80, 60};
  const double cx = 0.3, cy = -0.2, cz = 0.1, r = 1;
  const SphereSetup s = setup_sphere(cam, cx, cy, cz, r);
  FaceSpans spans;
  ScanCounters c;
  scan_sphere(s, vp, spans, c);
  EXPECT_EQ(spans.pixels(), 80u * 60u);
  EXPECT_EQ(spans.size(), 60u);
  EXPECT_LE(c.pixel_tests, 2u * 60u);  // both ends of each row, nothing else
  for (int j = 0; j < 60; j += 7)
    for (int i = 0; i < 80; i += 7) {
      SphereHit h;
      ASSERT_TRUE(sphere_hit(s, i, j, &h));
      EXPECT_TRUE(h.inside);
      EXPECT_LT(h.t_in, 0);
      EXPECT_EQ(h.t, h.t_out);
      const double a = (i - cam.ox) / cam.sx, b = (cam.oy - j) / cam.sy;
      const double px = h.t * a - cx, py = h.t * b - cy, pz = h.t - cz;
      EXPECT_NEAR(std::sqrt(px * px + py * py + pz * pz), r, 1e-13);
    }
}

TEST(SphereSpan, BehindTheEyeIsInvisible) {
  CameraPlane cam{true, 100, 100, 50, 50};
  const Viewport vp{0, 0, 100, 100};
  for (double r : {0.5, 4.0, 4.99}) {
    const SphereSetup s = setup_sphere(cam, 0.1, -0.2, -5, r);
    int i0, i1, j0, j1;
    EXPECT_FALSE(sphere_pixel_range(s, vp, &i0, &i1, &j0, &j1)) << r;
    FaceSpans spans;
    ScanCounters c;
    scan_sphere(s, vp, spans, c);
    EXPECT_EQ(spans.size(), 0u) << r;
    EXPECT_EQ(c.pixel_tests, 0u);
    SphereHit h;
    EXPECT_FALSE(sphere_hit(s, 50, 50, &h));
  }
  // Just containing the eye: everything, seen from inside.
  const SphereSetup s = setup_sphere(cam, 0.1, -0.2, -5, 5.01);
  FaceSpans spans;
  ScanCounters c;
  scan_sphere(s, vp, spans, c);
  EXPECT_EQ(spans.pixels(), 100u * 100u);
}

TEST(SphereSpan, OrthographicEyePlaneCutSeesExitSurface) {
  // Centre on the eye plane: the visible disk is the full radius, all exits.
  CameraPlane cam{false, 10, 10, 50, 50};
  const SphereSetup s = setup_sphere(cam, 0, 0, 0, 2);
  FaceSpans spans;
  ScanCounters c;
  scan_sphere(s, {0, 0, 100, 100}, spans, c);
  uint64_t n = 0;
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 100; ++i) {
      const int p = i - 50, q = 50 - j;  // a = p/10, b = q/10: classify in integers
      if (p * p + q * q == 400) continue;
      const double d2 = (p * p + q * q) / 100.0;
      SphereHit h;
      const bool hit = sphere_hit(s, i, j, &h);
      ASSERT_EQ(hit, p * p + q * q < 400) << i << "," << j;
      if (!hit) continue;
      ++n;
      EXPECT_TRUE(h.inside);
      EXPECT_NEAR(h.t, std::sqrt(4 - d2), 1e-14);
    }
  EXPECT_GE(spans.pixels(), n);
  EXPECT_LE(spans.pixels(), n + 12);  // the 12 centres exactly on the rim may round either way
  // Centre 1 behind the eye plane: visible disk radius² = 4 − 1.
  const SphereSetup s2 = setup_sphere(cam, 0, 0, -1, 2);
  FaceSpans sp2;
  scan_sphere(s2, {0, 0, 100, 100}, sp2, c);
  uint64_t want = 0;
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 100; ++i) {
      const int p = i - 50, q = 50 - j;
      want += p * p + q * q < 300;  // never equal: 300 is not a sum of two squares
    }
  EXPECT_EQ(sp2.pixels(), want);
}

// Area of the conic {(c·d)² − k|d|² >= 0} in the camera plane (pixels),
// computed in long double from its centre and matrix; also the axis extents
// when cy = 0.
struct Ellipse {
  LD area, half_w, half_h;
};
Ellipse conic_ellipse(const CameraPlane& cam, LD cx, LD cy, LD cz, LD r) {
  const LD k = cx * cx + cy * cy + cz * cz - r * r;
  // F(u) = uᵀPu + 2gᵀu + h
  const LD P00 = cx * cx - k, P01 = cx * cy, P11 = cy * cy - k;
  const LD g0 = cz * cx, g1 = cz * cy, h = cz * cz - k;
  const LD det = P00 * P11 - P01 * P01;
  const LD u0 = -(P11 * g0 - P01 * g1) / det, u1 = -(-P01 * g0 + P00 * g1) / det;
  const LD F0 = h + g0 * u0 + g1 * u1;
  Ellipse e;
  e.area = std::numbers::pi_v<LD> * F0 / std::sqrt(det) * LD(cam.sx) * LD(cam.sy);
  e.half_w = std::sqrt(F0 / -P00) * cam.sx;  // valid when cy = 0 (axis-aligned)
  e.half_h = std::sqrt(F0 / -P11) * cam.sy;
  return e;
}

TEST(SphereSpan, OffAxisPerspectiveIsTheConicEllipse) {
  CameraPlane cam{true, 150, 150, 40, 150};
  const Viewport vp{0, 0, 400, 300};
  {  // beside the axis in x only: axis-aligned ellipse, wider than tall
    const SphereSetup s = setup_sphere(cam, 8, 0, 10, 3);
    const Ellipse e = conic_ellipse(cam, 8, 0, 10, 3);
    FaceSpans spans;
    ScanCounters c;
    scan_sphere(s, vp, spans, c);
    int widest = 0;
    for (const RowSpan& r : spans.rows) widest = std::max(widest, r.x1 - r.x0 + 1);
    EXPECT_NEAR(widest, 2 * double(e.half_w), 2.0);
    EXPECT_NEAR(double(spans.size()), 2 * double(e.half_h), 2.0);
    EXPECT_GT(e.half_w - e.half_h, 10);  // truly elongated, not a circle
    const double perimeter = 2 * std::numbers::pi * double(e.half_w);
    EXPECT_NEAR(double(spans.pixels()), double(e.area), perimeter);
    // The analytic guess is nearly exact: a few tests per row.
    EXPECT_LE(c.pixel_tests, 5 * spans.size());
  }
  {  // off-axis in both: rotated ellipse
    const SphereSetup s = setup_sphere(cam, 5, -4, 9, 2.5);
    const Ellipse e = conic_ellipse(cam, 5, -4, 9, 2.5);
    FaceSpans spans;
    ScanCounters c;
    scan_sphere(s, vp, spans, c);
    EXPECT_NEAR(double(spans.pixels()), double(e.area), 2 * std::numbers::pi * std::sqrt(double(e.area)));
    // A circle of the on-axis apparent radius would be visibly smaller.
    const double circle = std::numbers::pi * std::pow(150 * 2.5 / std::sqrt(81 + 25 + 16 - 6.25), 2);
    EXPECT_GT(double(spans.pixels()), circle * 1.1);
  }
}

TEST(SphereSpan, SubPixelSpheresCoverZeroOrOnePixel) {
  CameraPlane cam{true, 100, 100, 0, 0};
  // Projected radius 0.3 px centred on pixel (10, 10) exactly: one pixel.
  const double z = 20;
  const SphereSetup s = setup_sphere(cam, 10.0 / 100 * z, -10.0 / 100 * z, z, 0.3 / 100 * z);
  FaceSpans spans;
  ScanCounters c;
  scan_sphere(s, {0, 0, 40, 40}, spans, c);
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_EQ(spans.rows[0].y, 10);
  EXPECT_EQ(spans.rows[0].x0, 10);
  EXPECT_EQ(spans.rows[0].x1, 10);
  // Centred between four pixel centres: none.
  const SphereSetup s2 = setup_sphere(cam, 10.5 / 100 * z, -10.5 / 100 * z, z, 0.3 / 100 * z);
  FaceSpans sp2;
  scan_sphere(s2, {0, 0, 40, 40}, sp2, c);
  EXPECT_EQ(sp2.size(), 0u);
}

TEST(SphereSpan, TouchingSpheresShareNoPixelAndTileTheUnion) {
  // Orthographic, two equal spheres touching at the origin along x: each
  // pixel centre with a < 0 belongs to the left disk only, a > 0 to the right.
  CameraPlane cam{false, 20, 20, 100.5, 60.5};
  const Viewport vp{0, 0, 201, 121};
  const SphereSetup L = setup_sphere(cam, -2, 0, 5, 2), R = setup_sphere(cam, 2, 0, 5, 2);
  FaceSpans sl, sr;
  ScanCounters c;
  scan_sphere(L, vp, sl, c);
  scan_sphere(R, vp, sr, c);
  // Mirror images of each other (the mapping is symmetric about a = 0).
  ASSERT_EQ(sl.size(), sr.size());
  for (size_t k = 0; k < sl.size(); ++k) {
    EXPECT_EQ(sl.rows[k].y, sr.rows[k].y);
    EXPECT_EQ(sl.rows[k].x1 + sr.rows[k].x0, 201);
    EXPECT_EQ(sl.rows[k].x0 + sr.rows[k].x1, 201);
    EXPECT_LT(sl.rows[k].x1, sr.rows[k].x0);  // no shared pixel
  }
  // Disk of radius 40 px each.
  EXPECT_NEAR(double(sl.pixels()), std::numbers::pi * 1600, 2 * std::numbers::pi * 40);
}

}  // namespace
}  // namespace zs
