// The surface renderer's images (src/render/surfaces/surface_renderer.h):
// analytic shadows (map and exact), near clipping, and bit-identical images
// for any thread and tile count, with the empty-tile early out on or off, and
// with RGBA-only tiles.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "raster/image_sink.h"
#include "render/surfaces/surface_renderer.h"
#include "support/test_surface_meshes.h"

namespace zs {
namespace {

SurfaceRenderSettings settings_for(const Camera& cam, uint32_t W, uint32_t H, size_t surfaces) {
  SurfaceRenderSettings s;
  s.width = W;
  s.height = H;
  s.camera = cam;
  s.colors.assign(surfaces, glm::dvec3(0.8));
  s.tile_size = 16;
  return s;
}

// A square occluder of side 1 at height 1 over a ground square, a light
// straight down: the shadow is the occluder's projection. Exact mode gets
// every ground pixel right; a map only errs within a texel or two of the edge.
TEST(Surfaces, AnalyticShadowOfASquareMapAndExact) {
  TriangleMesh m = test::square_over_ground();
  compute_point_normals(m);
  const Camera cam = test::perspective_camera({0.2, 6, 4}, {0, 0, 0}, 50);
  const uint32_t W = 120, H = 100;
  for (ShadowMode mode : {ShadowMode::Exact, ShadowMode::Map}) {
    SurfaceRenderSettings s = settings_for(cam, W, H, 2);
    s.lights = {Light{}};
    s.lights[0].direction = {0, -1, 0};
    s.shadows.mode = mode;
    s.shadows.map_size = 512;
    s.threads = 2;
    SurfaceRenderer r(m, s);
    ImageSink sink(r.grid());
    r.render_tiles(sink, nullptr);
    const View view(cam, W, H);
    // Texel size of the fitted map, from the visible ground's extent (at most the ground's 6 units).
    const double texel = 6.0 / 512 * 1.1;
    uint32_t ground = 0, wrong = 0, wrong_far = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        glm::dvec3 o, d;
        view.ray(x, y, &o, &d);
        // Does the ray hit the ground (not the occluder) first?
        const double tg = -o.y / d.y, to = (1 - o.y) / d.y;
        const glm::dvec3 g = o + d * tg, q = o + d * to;
        if (!(tg > 0) || std::abs(g.x) > 3 || std::abs(g.z) > 3) continue;
        if (to > 0 && std::abs(q.x) <= 0.5 && std::abs(q.z) <= 0.5) continue;
        const double edge = std::max(std::abs(g.x), std::abs(g.z)) - 0.5;  // < 0 inside the shadow
        if (std::abs(edge) < 1e-9) continue;
        ++ground;
        const float lit = sink.channel(x, y, 0);
        const bool ok = lit == (edge > 0 ? 1.f : 0.f);
        wrong += !ok;
        wrong_far += !ok && std::abs(edge) > 2 * texel;
        const double zg = glm::dot(g - cam.eye, view.forward());
        EXPECT_NEAR(sink.z[size_t(y) * W + x], zg, 1e-6 * zg);  // stored as float
      }
    EXPECT_GT(ground, W * H / 3);
    if (mode == ShadowMode::Exact) {
      EXPECT_EQ(wrong, 0u);
    } else {
      EXPECT_EQ(wrong_far, 0u);
      EXPECT_LT(wrong, ground / 50);
    }
  }
}

// A ground plane running behind a perspective eye just above it: near
// clipping keeps exactly the pixels whose rays meet the plane in the square.
TEST(Surfaces, NearClippedGroundCoversExactlyItsPixels) {
  TriangleMesh m;
  m.points = {{-50, 0, -50}, {50, 0, -50}, {50, 0, 50}, {-50, 0, 50}};
  m.tris = {{0, 2, 1}, {0, 3, 2}};
  m.surface = {0, 0};
  compute_point_normals(m);
  const Camera cam = test::perspective_camera({0.3, 0.5, 0.2}, {0.3, -0.2, -2}, 80);
  const uint32_t W = 90, H = 70;
  SurfaceRenderSettings s = settings_for(cam, W, H, 1);
  s.lights.clear();
  SurfaceRenderer r(m, s);
  ImageSink sink(r.grid());
  r.render_tiles(sink, nullptr);
  EXPECT_GT(r.stats().project.near_clipped, 0u);
  const View view(cam, W, H);
  uint32_t hits = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      glm::dvec3 o, d;
      view.ray(x, y, &o, &d);
      const double t = -o.y / d.y;
      const glm::dvec3 g = o + d * t;
      const double inside = 50 - std::max(std::abs(g.x), std::abs(g.z));
      if (std::abs(inside) < 1e-6) continue;
      const bool expect = t > 0 && inside > 0;
      hits += expect;
      EXPECT_EQ(sink.image.at(x, y)[3] == 1.f, expect) << x << "," << y;
    }
  EXPECT_GT(hits, W * H / 4);
}

// Threads and tiles change no bit: every channel, both shadow modes, with
// a spot light and a directional one, n-SM and PCF.
// The cube raised over a ground quad (surface 1), and a camera seeing both.
TriangleMesh cube_over_ground() {
  TriangleMesh m = test::cube();
  TriangleMesh ground;
  ground.points = {{-3, 0, -3}, {4, 0, -3}, {4, 0, 4}, {-3, 0, 4}};
  ground.tris = {{0, 2, 1}, {0, 3, 2}};
  for (glm::dvec3& p : m.points) p += glm::dvec3(0, 0.3, 0);
  append_mesh(m, ground, 1);
  compute_point_normals(m);
  return m;
}
Camera cube_camera() { return test::perspective_camera({3, 4, 5}, {0.5, 0.3, 0.5}, 45); }

TEST(Surfaces, ThreadsAndTilesGiveBitIdenticalImages) {
  const TriangleMesh m = cube_over_ground();
  const Camera cam = cube_camera();
  for (ShadowMode mode : {ShadowMode::Map, ShadowMode::Exact}) {
    std::vector<std::vector<float>> images;
    for (auto [threads, tile] : {std::pair{1, 16u}, std::pair{2, 16u}, std::pair{2, 64u}, std::pair{1, 8u}}) {
      SurfaceRenderSettings s = settings_for(cam, 100, 77, 2);
      Light spot;
      spot.type = LightType::Spot;
      spot.position = {2, 5, -1};
      spot.target = {0.5, 0, 0.5};
      spot.fov_deg = 70;
      s.lights = {Light{}, spot};
      s.shadows.mode = mode;
      s.shadows.depths = 3;
      s.shadows.pcf = 9;
      s.shadows.map_size = 256;
      s.threads = threads;
      s.tile_size = tile;
      SurfaceRenderer r(m, s);
      ImageSink sink(r.grid());
      r.render_tiles(sink, nullptr);
      std::vector<float> all(sink.image.rgba.begin(), sink.image.rgba.end());
      all.insert(all.end(), sink.z.begin(), sink.z.end());
      all.insert(all.end(), sink.extra.begin(), sink.extra.end());
      images.push_back(all);
      EXPECT_GT(r.stats().tiles.rendered_pixels, 1000u);
    }
    for (size_t i = 1; i < images.size(); ++i)
      EXPECT_EQ(0, std::memcmp(images[0].data(), images[i].data(), images[0].size() * sizeof(float)))
          << to_string(mode) << " run " << i;
  }
}

// The early out of lookups in empty map tiles (surface_renderer.cpp) is
// exact: on and off give the same bits, for n-SMs and PCF kernels, two
// lights, both projections and two tile sizes, while it decides part of the
// tests.
TEST(Surfaces, EmptyTileEarlyOutChangesNoBit) {
  const TriangleMesh m = cube_over_ground();
  // Rolled cameras, so that depth changes along the ground's rows too.
  Camera persp = cube_camera();
  persp.up = {0.5, 1, 0};
  Camera ortho = persp;
  ortho.projection = Projection::Orthographic;
  ortho.height = 5;
  struct Config {
    uint32_t depths, pcf;
  };
  for (const Camera& cam : {persp, ortho})
    for (Config c : {Config{1, 1}, Config{2, 4}, Config{3, 9}, Config{1, 16}})
      for (uint32_t tile : {16u, 64u}) {
        std::vector<float> images[2];
        for (int early = 0; early < 2; ++early) {
          SurfaceRenderSettings s = settings_for(cam, 150, 110, 2);
          Light side;
          side.direction = {-1, -0.7, 0.4};
          s.lights = {Light{}, side};
          s.shadows.depths = c.depths;
          s.shadows.pcf = c.pcf;
          s.shadows.map_size = 512;
          s.tile_size = tile;
          s.empty_tile_early_out = early == 1;
          SurfaceRenderer r(m, s);
          ImageSink sink(r.grid());
          r.render_tiles(sink, nullptr);
          images[early].assign(sink.image.rgba.begin(), sink.image.rgba.end());
          images[early].insert(images[early].end(), sink.z.begin(), sink.z.end());
          images[early].insert(images[early].end(), sink.extra.begin(), sink.extra.end());
          const SurfaceTileTotals& T = r.stats().tiles;
          if (early) {
            EXPECT_GT(T.shadow_tests_empty, T.shadow_tests / 10) << c.depths << "-SM PCF " << c.pcf;
            EXPECT_LT(T.shadow_tests_empty, T.shadow_tests * 9 / 10);
          } else {
            EXPECT_EQ(T.shadow_tests_empty, 0u);
          }
        }
        ASSERT_EQ(images[0].size(), images[1].size());
        EXPECT_EQ(0, std::memcmp(images[0].data(), images[1].data(), images[0].size() * sizeof(float)))
            << (cam.projection == Projection::Perspective ? "perspective " : "orthographic ") << c.depths
            << "-SM PCF " << c.pcf << " tile " << tile;
      }
}

TEST(Surfaces, RgbaOnlyTilesHoldTheSameColours) {
  // depth_and_lit off (8-bit outputs): four channels, the same RGBA bits.
  const TriangleMesh m = cube_over_ground();
  const Camera cam = cube_camera();
  std::vector<float> rgba[2];
  for (int only = 0; only < 2; ++only) {
    SurfaceRenderSettings s = settings_for(cam, 100, 77, 2);
    const double bg[4] = {0.1, 0.2, 0.3, 0.5};
    std::copy(bg, bg + 4, s.background);
    s.lights = {Light{}};
    s.shadows.map_size = 256;
    s.depth_and_lit = only == 0;
    SurfaceRenderer r(m, s);
    EXPECT_EQ(r.grid().channels, only ? 4u : 6u);
    ImageSink sink(r.grid());
    r.render_tiles(sink, nullptr);
    rgba[only].assign(sink.image.rgba.begin(), sink.image.rgba.end());
    EXPECT_GT(r.stats().tiles.rendered_pixels, 1000u);
    EXPECT_LT(r.stats().tiles.rendered_pixels, 7700u);  // the background shows too
  }
  ASSERT_EQ(rgba[0].size(), rgba[1].size());
  EXPECT_EQ(0, std::memcmp(rgba[0].data(), rgba[1].data(), rgba[0].size() * sizeof(float)));
}

}  // namespace
}  // namespace zs
