// The opaque sphere renderer against closed forms (both projections,
// interpenetrating spheres, eye inside), and its invariants: culling,
// tiles and threads never change a bit; the centre-disc map is never nearer
// than the exact depth.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "raster/image_sink.h"
#include "geometry/spheres/sphere_colors.h"
#include "lighting/occlusion_map.h"
#include "render/spheres/sphere_renderer.h"
#include "render/spheres/sphere_visibility.h"

namespace zs {
namespace {

struct Rendered {
  Image rgba;
  std::vector<float> z;
  SphereStats stats;
};

Rendered render(const SphereSet& s, const SphereRenderSettings& rs) {
  const std::vector<glm::vec4> colors = sphere_colors(s, SphereColorMode::Element, TransferFunction());
  const SphereGrid g = build_sphere_grid(s, rs.grid);
  SphereRenderer r(s, colors, g, rs);
  ImageSink sink(r.grid());
  r.render_tiles(sink, nullptr);
  return {std::move(sink.image), std::move(sink.z), r.stats()};
}

// The visible depth along the ray through pixel (i, j), from the ray in world
// space (origin, unit direction), in long double: +inf when missed.
long double closed_form_depth(const View& v, int i, int j, const glm::dvec3& c, double r) {
  glm::dvec3 o, u;
  v.ray(i, j, &o, &u);
  long double oc[3] = {(long double)c.x - o.x, (long double)c.y - o.y, (long double)c.z - o.z};
  const long double b = oc[0] * u.x + oc[1] * u.y + oc[2] * u.z;
  const long double cc = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - (long double)r * r;
  const long double disc = b * b - cc;
  if (disc < 0) return INFINITY;
  const long double t0 = b - std::sqrt(disc), t1 = b + std::sqrt(disc);
  const long double t = t0 > 0 ? t0 : t1;
  if (!(t > 0)) return INFINITY;
  const glm::dvec3 f = v.forward();
  return t * (u.x * f.x + u.y * f.y + u.z * f.z) + ((o.x - v.eye().x) * f.x + (o.y - v.eye().y) * f.y + (o.z - v.eye().z) * f.z);
}

SphereRenderSettings settings(Projection p, uint32_t w, uint32_t h) {
  SphereRenderSettings rs;
  rs.width = w, rs.height = h;
  rs.camera.projection = p;
  rs.camera.eye = {0.3, -0.2, 10};
  rs.camera.target = {0, 0, 0};
  rs.camera.height = 6;
  rs.camera.fov_y = 40;
  rs.tile_size = 16;
  return rs;
}

// Every pixel's Z equals the nearest closed-form depth over the spheres
// (within rounding), and coverage agrees away from grazing rays.
void expect_exact_depths(const SphereSet& s, const SphereRenderSettings& rs, const Rendered& out) {
  const View v(rs.camera, rs.width, rs.height);
  int checked = 0, grazing = 0;
  for (uint32_t j = 0; j < rs.height; ++j)
    for (uint32_t i = 0; i < rs.width; ++i) {
      long double best = INFINITY;
      for (size_t k = 0; k < s.size(); ++k) best = std::min(best, closed_form_depth(v, int(i), int(j), s.centres[k], s.radii[k]));
      const float z = out.z[size_t(j) * rs.width + i];
      if (std::isinf(best) != std::isinf(z)) {
        ++grazing;  // a ray tangent to within rounding
        continue;
      }
      if (std::isinf(best)) continue;
      EXPECT_NEAR(double(z), double(best), 1e-5 * double(best)) << i << "," << j;
      ++checked;
    }
  EXPECT_GT(checked, 100);
  EXPECT_LE(grazing, 2);
}

TEST(SphereRenderer, ExactDepthAndCoverageOfOneSphereBothProjections) {
  SphereSet s;
  s.centres = {{0.4, -0.3, 1.0}};
  s.radii = {1.7};
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    const SphereRenderSettings rs = settings(p, 64, 48);
    const Rendered out = render(s, rs);
    expect_exact_depths(s, rs, out);
    // Coverage: alpha 1 exactly where Z is finite, the background elsewhere.
    for (size_t q = 0; q < out.z.size(); ++q) EXPECT_EQ(out.rgba.rgba[q * 4 + 3], std::isinf(out.z[q]) ? 0.f : 1.f);
  }
}

TEST(SphereRenderer, InterpenetratingSpheresMeetOnTheirIntersectionCurve) {
  SphereSet s;
  s.centres = {{-0.6, 0.1, 0.0}, {0.5, -0.1, 0.6}, {0.1, 0.9, -0.4}};
  s.radii = {1.2, 1.0, 0.8};
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    const SphereRenderSettings rs = settings(p, 80, 80);
    const Rendered out = render(s, rs);
    expect_exact_depths(s, rs, out);
  }
}

// Large nested spheres (C2's kind): most exact hits are skipped by the
// per-block depth bounds, and every pixel's depth is still the brute-force
// nearest hit over all spheres, bit for bit.
TEST(SphereRenderer, NestedLargeSpheresEqualBruteForce) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1), ur(0.2, 1.6);
  SphereSet s;
  for (int k = 0; k < 300; ++k) {
    s.centres.push_back({2.0 * u(rng), 2.0 * u(rng), 2.0 * u(rng)});
    s.radii.push_back(ur(rng));
  }
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings rs = settings(p, 96, 80);
    rs.culling = false;  // every sphere reaches the tiles: their tests alone
    const Rendered out = render(s, rs);
    const View v(rs.camera, rs.width, rs.height);
    const CameraPlane cam = camera_plane(v);
    std::vector<SphereSetup> su;
    for (size_t k = 0; k < s.size(); ++k) {
      const glm::dvec3 c = to_camera(v, s.centres[k]);
      su.push_back(setup_sphere(cam, c.x, c.y, c.z, s.radii[k]));
    }
    uint64_t hit_pixels = 0, hits = 0;
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        double best = INFINITY;
        for (const SphereSetup& q : su) {
          SphereHit h;
          if (sphere_hit(q, i, j, &h)) best = std::min(best, h.t), ++hits;
        }
        hit_pixels += std::isfinite(best);
        ASSERT_EQ(out.z[size_t(j) * rs.width + i], float(best)) << i << "," << j;
      }
    EXPECT_GT(hit_pixels, 3000u);
    // The bounds did the work: the renderer computed a fraction of the
    // ray-sphere hits there are.
    EXPECT_LT(out.stats.fragments, hits / 4);
  }
}

TEST(SphereRenderer, EyeInsideASphereSeesItsFarSurface) {
  SphereSet s;
  s.centres = {{0, 0, 9.5}, {0, 0, 0}};
  s.radii = {2.0, 1.0};  // the eye (0.3, -0.2, 10) is inside the first
  SphereRenderSettings rs = settings(Projection::Perspective, 40, 40);
  const Rendered out = render(s, rs);
  expect_exact_depths(s, rs, out);
  for (float z : out.z) EXPECT_TRUE(std::isfinite(z));  // every ray leaves the sphere it starts in
}

TEST(SphereRenderer, SphereBehindTheCameraIsNotDrawn) {
  SphereSet s;
  s.centres = {{0, 0, 14}};
  s.radii = {1.0};
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    const Rendered out = render(s, settings(p, 32, 32));
    for (float z : out.z) EXPECT_TRUE(std::isinf(z));
    EXPECT_EQ(out.stats.rendered_pixels, 0u);
  }
}

// A dense clustered set: many spheres hidden, so the culling has work.
SphereSet cluster_set(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  SphereSet s;
  for (size_t i = 0; i < n; ++i) {
    const bool dense = i % 4 != 0;
    const double e = dense ? 1.2 : 3.5;
    s.centres.push_back({e * u(rng), e * u(rng), e * u(rng)});
    s.radii.push_back(dense ? 0.05 + 0.1 * (u(rng) + 1) : 0.03 + 0.02 * (u(rng) + 1));
  }
  return s;
}

TEST(SphereRenderer, CullingIsLosslessBitForBit) {
  const SphereSet s = cluster_set(20000, 7);
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings on = settings(p, 96, 80), off = on;
    off.culling = false;
    const Rendered a = render(s, on), b = render(s, off);
    EXPECT_EQ(a.rgba.rgba, b.rgba.rgba);
    EXPECT_EQ(0, std::memcmp(a.z.data(), b.z.data(), a.z.size() * 4));
    // The culling did cull: cells, and spheres by the pyramid.
    EXPECT_GT(a.stats.vis.spheres_occluded_cells + a.stats.vis.spheres_pyramid_culled, 1000u);
    EXPECT_LT(a.stats.vis.spheres_visible, b.stats.vis.spheres_visible);
  }
}

TEST(SphereRenderer, ViewCullingDropsCellsOutsideTheView) {
  SphereSet s = cluster_set(5000, 3);
  for (size_t i = 0; i < 2000; ++i) s.centres[i].x += 40;  // far to the right, out of view
  SphereRenderSettings on = settings(Projection::Perspective, 64, 64), off = on;
  off.culling = false;
  const Rendered a = render(s, on), b = render(s, off);
  EXPECT_EQ(a.rgba.rgba, b.rgba.rgba);
  EXPECT_GT(a.stats.vis.cells_view_culled, 0u);
  EXPECT_GT(a.stats.vis.spheres_view_culled, 0u);
}

TEST(SphereRenderer, TilesAndThreadsGiveBitIdenticalImages) {
  const SphereSet s = cluster_set(4000, 11);
  SphereRenderSettings base = settings(Projection::Perspective, 70, 53);
  const Rendered ref = render(s, base);
  for (uint32_t tile : {1u, 7u, 64u, 200u})
    for (int threads : {1, 2}) {
      SphereRenderSettings rs = base;
      rs.tile_size = tile, rs.threads = threads;
      const Rendered out = render(s, rs);
      EXPECT_EQ(out.rgba.rgba, ref.rgba.rgba) << tile << " " << threads;
      EXPECT_EQ(0, std::memcmp(out.z.data(), ref.z.data(), ref.z.size() * 4));
    }
}

TEST(SphereRenderer, CentreDiscMapIsNeverNearerThanTheExactDepth) {
  const SphereSet s = cluster_set(3000, 5);
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    const SphereRenderSettings rs = settings(p, 90, 70);
    const Rendered exact = render(s, rs);
    const View v(rs.camera, rs.width, rs.height);
    OcclusionMap map(rs.width, rs.height);  // one texel per pixel at this size
    ASSERT_EQ(map.block(), 1u);
    uint64_t written = 0;
    for (size_t k = 0; k < s.size(); ++k) {
      const glm::dvec3 c = to_camera(v, s.centres[k]);
      if (!(c.z - s.radii[k] > 0)) continue;
      const double inv = v.perspective() ? 1 / c.z : 1.0;
      map.write_disc(v.scale_x() * c.x * inv + v.offset_x(), v.offset_y() - v.scale_y() * c.y * inv,
                     v.scale_x() * s.radii[k] * inv, c.z);
    }
    for (uint32_t j = 0; j < rs.height; ++j)
      for (uint32_t i = 0; i < rs.width; ++i) {
        const double m = map.texel(i, j);
        if (std::isinf(m)) continue;
        ++written;
        EXPECT_GE(m, double(exact.z[size_t(j) * rs.width + i])) << i << "," << j;
      }
    EXPECT_GT(written, 1000u);
  }
}

// The grid only changes the work: every resolution, "auto" included, gives the
// same image as no culling at all; "auto" follows the set's size.
TEST(SphereRenderer, GridResolutionChangesNoPixel) {
  EXPECT_EQ(auto_sphere_grid(0), 9u);
  EXPECT_EQ(auto_sphere_grid(3000), 9u);
  EXPECT_EQ(auto_sphere_grid(1000000), 11u);
  EXPECT_EQ(auto_sphere_grid(27000000), 32u);
  EXPECT_EQ(auto_sphere_grid(uint64_t(1) << 40), 64u);
  const SphereSet s = cluster_set(3000, 5);
  EXPECT_EQ(build_sphere_grid(s, 0).n, 9u);
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings off = settings(p, 90, 70);
    off.culling = false;
    const Rendered ref = render(s, off);
    for (uint32_t n : {0u, 1u, 4u, 17u, 40u}) {
      SphereRenderSettings on = settings(p, 90, 70);
      on.grid = n;
      const Rendered a = render(s, on);
      EXPECT_EQ(a.rgba.rgba, ref.rgba.rgba) << n;
      EXPECT_EQ(0, std::memcmp(a.z.data(), ref.z.data(), ref.z.size() * 4)) << n;
      EXPECT_EQ(a.stats.vis.cells, (n ? n : 9u) * (n ? n : 9u) * (n ? n : 9u));
    }
  }
}

// Large spheres on screen: the occlusion map takes coarse texels (a block of
// pixels each); culling must still change nothing.
TEST(SphereRenderer, CullingIsLosslessWithCoarseOcclusionTexels) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  SphereSet s;
  for (int i = 0; i < 400; ++i) {
    s.centres.push_back({4 * u(rng), 4 * u(rng), 4 * u(rng)});
    s.radii.push_back(0.6 + 0.3 * u(rng));
  }
  for (Projection p : {Projection::Orthographic, Projection::Perspective}) {
    SphereRenderSettings on = settings(p, 160, 120), off = on;
    on.camera.eye = {1, 1.5, 9};
    on.camera.height = 5;
    off = on;
    off.culling = false;
    const Rendered a = render(s, on), b = render(s, off);
    EXPECT_EQ(a.rgba.rgba, b.rgba.rgba);
    EXPECT_EQ(0, std::memcmp(a.z.data(), b.z.data(), a.z.size() * 4));
    EXPECT_GT(a.stats.vis.spheres_occluded_cells + a.stats.vis.spheres_pyramid_culled, 50u);
  }
}

// A coarse texel takes a disc only where the disc covers every pixel centre of
// its block (brute force over the block's centres).
TEST(SphereRenderer, CoarseOcclusionTexelsNeedFullCover) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const uint32_t w = 37 + uint32_t(40 * u(rng)), h = 23 + uint32_t(40 * u(rng));
    OcclusionMap m(w, h, 8);  // blocks of several pixels
    const double X = w * u(rng), Y = h * u(rng), rho = 2 + 15 * u(rng);
    m.write_disc(X, Y, rho, 1.0);
    const uint32_t s = m.block();
    ASSERT_GT(s, 1u);
    for (uint32_t ty = 0; ty < m.texels_y(); ++ty)
      for (uint32_t tx = 0; tx < m.texels_x(); ++tx) {
        bool all_in = true;
        for (uint32_t y = ty * s; y < std::min((ty + 1) * s, h); ++y)
          for (uint32_t x = tx * s; x < std::min((tx + 1) * s, w); ++x)
            all_in = all_in && (x - X) * (x - X) + (y - Y) * (y - Y) <= rho * rho;
        if (!all_in) EXPECT_TRUE(std::isinf(m.texel(tx, ty))) << trial << ": " << tx << "," << ty;
      }
  }
}

TEST(SphereRenderer, PyramidTestUsesOneLevelOfAtMostTwoByTwo) {
  OcclusionMap m(64, 64);
  // Everything near (depth 1) except one texel at the far end (+inf).
  for (int k = 0; k < 64; ++k) m.write_disc(31.5, 31.5, 200, 1.0);
  m.write_disc(0, 0, 0, 0);  // no-op
  m.build_pyramid();
  EXPECT_TRUE(m.hidden_pyramid(10, 20, 10, 20, 2.0));
  EXPECT_FALSE(m.hidden_pyramid(10, 20, 10, 20, 0.5));
  OcclusionMap hole(64, 64);
  hole.write_disc(31.5, 31.5, 200, 1.0);
  // Carve nothing, but a box reaching past the image is clamped and still hidden.
  hole.build_pyramid();
  EXPECT_TRUE(hole.hidden_pyramid(-5, 70, -5, 70, 2.0));
  // A map with an empty texel under the box: not hidden, even if the rest is near.
  OcclusionMap part(64, 64);
  part.write_disc(10, 10, 8, 1.0);
  part.build_pyramid();
  EXPECT_FALSE(part.hidden_pyramid(8, 12, 8, 12, 2.0) && part.hidden_pyramid(20, 24, 20, 24, 2.0));
  EXPECT_TRUE(part.hidden_pyramid(9, 11, 9, 11, 2.0));
  EXPECT_FALSE(part.hidden_pyramid(20, 24, 20, 24, 2.0));
}

// A sphere small on screen is tried at each pixel centre of its box: one whose
// only hit lies behind the map is dropped even though its box reaches an
// empty texel (where the pyramid test cannot drop it), and the image does
// not change.
TEST(SphereRenderer, SmallSphereHiddenAtItsEveryHitIsDropped) {
  SphereRenderSettings rs = settings(Projection::Orthographic, 64, 64);
  rs.camera.eye = {0, 0, 30};  // the occluder wholly in front of the eye plane
  rs.camera.height = 64;  // one world unit per pixel
  rs.grid = 1;
  rs.threads = 1;
  const View v(rs.camera, rs.width, rs.height);
  // World point of pixel position (X, Y) at world depth z (camera looks down -z).
  auto at = [&](double X, double Y, double z) {
    return glm::dvec3((X - v.offset_x()) / v.scale_x() + v.eye().x, (v.offset_y() - Y) / v.scale_y() + v.eye().y, z);
  };
  SphereSet s;
  // The occluder: its disc covers pixel (30, 32), not (31, 32). (Small
  // enough for one map texel per pixel: occlusion_block.)
  s.centres.push_back(at(23, 32, 0));
  s.radii.push_back(7.5 / v.scale_x());
  // Behind it, a sphere whose box holds pixels 30..31 x 32..33 but whose
  // ray test hits (30, 32) only.
  s.centres.push_back(at(30.3, 32.3, -5));
  s.radii.push_back(0.72 / v.scale_x());
  SphereRenderSettings off = rs;
  off.culling = false;
  const Rendered a = render(s, rs), b = render(s, off);
  EXPECT_EQ(a.rgba.rgba, b.rgba.rgba);
  EXPECT_EQ(0, std::memcmp(a.z.data(), b.z.data(), a.z.size() * 4));
  EXPECT_EQ(a.stats.vis.spheres_pyramid_culled, 0u);
  EXPECT_EQ(a.stats.vis.spheres_pixel_culled, 1u);
  EXPECT_EQ(a.stats.vis.spheres_visible, 1u);
  EXPECT_EQ(b.stats.vis.spheres_visible, 2u);
}

TEST(SphereRenderer, ShadedCentrePixelIsBlinnPhongHeadOn) {
  SphereSet s;
  s.centres = {{0, 0, 0}};
  s.radii = {2.0};
  s.element = {8};  // oxygen: red
  SphereRenderSettings rs = settings(Projection::Orthographic, 33, 33);
  rs.camera.eye = {0, 0, 10};
  const Rendered out = render(s, rs);
  const float* px = out.rgba.at(16, 16);
  const glm::vec4 base = element_color(8);
  // n = v = l = (0, 0, 1): ambient + diffuse, plus the full highlight.
  const glm::dvec3 want = shade(rs.shading, {base.r, base.g, base.b}, {0, 0, 1}, {0, 0, 1});
  EXPECT_NEAR(px[0], want.r, 1e-6);
  EXPECT_NEAR(px[1], want.g, 1e-6);
  EXPECT_NEAR(px[2], want.b, 1e-6);
  EXPECT_EQ(px[3], 1.f);
  EXPECT_NEAR(out.z[16 * 33 + 16], 8.0, 1e-9);
}

}  // namespace
}  // namespace zs
