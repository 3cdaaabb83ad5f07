// Triangle surfaces and the surface renderer (src/geometry/triangles/, src/render/surfaces/):
// readers, culling counts, z-buffer depth against closed-form ray–triangle
// hits, near clipping, analytic shadows (map and exact), and bit-identical
// images for any thread and tile count.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "raster/depth_buffer.h"
#include "raster/image_sink.h"
#include "raster/triangle_bins.h"
#include "raster/zbuffer_tile.h"
#include "lighting/shadow_map.h"
#include "render/surfaces/surface_renderer.h"
#include "geometry/triangles/io/surface_reader.h"
#include "lighting/triangle_projection.h"
#include "test_paths.h"
#include "base/util/file_error.h"

namespace zs {
namespace {

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

const char* kCubeQuads =
    "OFF\n8 6 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";

TriangleMesh cube() {
  const auto dir = test::scratch_dir();
  write(dir / "cube.off", kCubeQuads);
  TriangleMesh m = read_surface((dir / "cube.off").string());
  compute_point_normals(m);
  return m;
}

TEST(Surfaces, ReadersSplitPolygonsAndCount) {
  const auto dir = test::scratch_dir();
  write(dir / "cube.off", kCubeQuads);
  SurfaceReadCounts c;
  const TriangleMesh m = read_surface((dir / "cube.off").string(), &c);
  EXPECT_EQ(m.num_points(), 8u);
  EXPECT_EQ(m.num_tris(), 12u);
  EXPECT_EQ(c.polygons, 6u);
  EXPECT_EQ(c.split, 6u);
  EXPECT_EQ(count_degenerate_tris(m), 0u);
  // Outward winding kept: every face normal points away from the centre.
  for (size_t t = 0; t < m.num_tris(); ++t) {
    const glm::dvec3 a = m.points[m.tris[t][0]];
    EXPECT_GT(glm::dot(face_normal(m, t), a - glm::dvec3(0.5)), 0) << t;
  }
  // The same square (a concave pentagon plus a triangle) as OBJ, ASCII STL and PLY.
  write(dir / "s.obj", "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 1 1 0\nv 0 2 0\nf 1 2 3 4 5\nl 1 3\n");
  const TriangleMesh o = read_surface((dir / "s.obj").string(), &c);
  EXPECT_EQ(o.num_tris(), 3u);  // the concave pentagon, ear-cut
  EXPECT_EQ(c.split, 1u);
  EXPECT_EQ(c.dropped, 1u);  // the line
  double area = 0;
  for (size_t t = 0; t < o.num_tris(); ++t) area += 0.5 * glm::length(face_normal(o, t));
  EXPECT_NEAR(area, 3.0, 1e-12);  // 2×2 square minus the notch of area 1
  write(dir / "s.stl",
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
        "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
  EXPECT_EQ(read_surface((dir / "s.stl").string()).num_tris(), 2u);
  write(dir / "s.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  EXPECT_EQ(read_surface((dir / "s.ply").string()).num_tris(), 2u);
  EXPECT_TRUE(is_surface_file((dir / "cube.off").string()));
  write(dir / "tets.off", "4 1\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 1 2 3\n");
  EXPECT_FALSE(is_surface_file((dir / "tets.off").string()));
}

TEST(Surfaces, MalformedFilesGiveOneLineErrorsNamingTheFile) {
  const auto dir = test::scratch_dir();
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"},
      {"short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"},
      {"empty.obj", ""},
      {"noface.obj", "v 0 0 0\nv 1 0 0\n"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
      {"junk.ply", "ply\nthis is not a ply header\n"},
      {"junk.stl", "solid x\nfacet nonsense\n"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"},
  };
  for (const auto& [name, text] : bad) {
    write(dir / name, text);
    const std::string path = (dir / name).string();
    try {
      read_surface(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const FileError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
  EXPECT_THROW(read_surface((dir / "missing.obj").string()), FileError);
}

// A convex closed mesh in a generic view: half its triangles face away.
TEST(Surfaces, BackFaceAndViewCullingCounts) {
  const TriangleMesh m = cube();
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {3.1, 2.3, 4.2};
  cam.target = {0.5, 0.5, 0.5};
  cam.fov_y = 40;
  ProjectedTriangles pt;
  ProjectCounts c;
  project_triangles(m, View(cam, 64, 64), {true, true, 1e-6}, &pt, &c);
  EXPECT_EQ(c.triangles, 12u);
  EXPECT_EQ(c.back_culled, 6u);
  EXPECT_EQ(c.view_culled, 0u);
  EXPECT_EQ(pt.corners.size(), 6u);
  // Looking away: every front face is outside the view.
  cam.target = cam.eye + (cam.eye - cam.target);
  ProjectCounts c2;
  project_triangles(m, View(cam, 64, 64), {true, true, 1e-6}, &pt, &c2);
  EXPECT_EQ(c2.view_culled + c2.back_culled, 12u);
  EXPECT_EQ(pt.corners.size(), 0u);
}

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
  TriangleMesh m;
  m.points = {{-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5},   // occluder
              {-3, 0, -3},     {3, 0, -3},     {3, 0, 3},     {-3, 0, 3}};       // ground
  m.tris = {{0, 2, 1}, {0, 3, 2}, {4, 6, 5}, {4, 7, 6}};
  m.surface = {0, 0, 1, 1};
  compute_point_normals(m);
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {0.2, 6, 4};
  cam.target = {0, 0, 0};
  cam.fov_y = 50;
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

// Caster culling (shadow_map.cpp): a ground under everything shadows nothing,
// so it is left out of the map and every lit count stays the same; with a
// receiver below the ground it is kept and shadows that receiver.
TEST(Surfaces, CasterCullingLeavesOutOnlyWhatShadowsNothing) {
  TriangleMesh m;
  m.points = {{-0.5, 1, -0.5}, {0.5, 1, -0.5}, {0.5, 1, 0.5}, {-0.5, 1, 0.5},   // occluder
              {-3, 0, -3},     {3, 0, -3},     {3, 0, 3},     {-3, 0, 3}};       // ground
  m.tris = {{0, 2, 1}, {0, 3, 2}, {4, 6, 5}, {4, 7, 6}};
  m.surface = {0, 0, 1, 1};
  Light light;
  light.direction = {0.3, -1, 0.2};
  const glm::dvec3 up(0, 1, 0);
  auto build = [&](bool cull, ShadowMapStats* st) {
    LightFit fit = start_fit(light);
    for (const glm::dvec3& p : m.points) fit.add(p);
    ShadowSettings s;
    s.map_size = 256;
    s.cull_casters = cull;
    return ShadowMap::build(m, light, fit, triangle_bounds(m), s, 2, st);
  };
  ShadowMapStats on, off;
  const ShadowMap a = build(true, &on), b = build(false, &off);
  EXPECT_EQ(on.casters_culled, 2u);  // the ground's two triangles
  EXPECT_EQ(off.casters_culled, 0u);
  EXPECT_EQ(on.casters, 2u);
  EXPECT_LT(on.texels_covered, off.texels_covered);
  uint32_t shadowed = 0;
  for (double x = -2.9; x < 2.9; x += 0.05)
    for (double z = -2.9; z < 2.9; z += 0.05) {
      const glm::dvec3 g(x, 0, z), o(0.45 * x / 2.9, 1, 0.45 * z / 2.9);
      ASSERT_EQ(a.lit_count(g, up), b.lit_count(g, up)) << x << "," << z;
      ASSERT_EQ(a.lit_count(o, up), b.lit_count(o, up)) << x << "," << z;
      shadowed += a.lit_count(g, up) == 0;
    }
  EXPECT_GT(shadowed, 100u);
  // A receiver below the ground: the ground must stay a caster.
  m.points.push_back({0, -1, 0});
  m.points.push_back({0.1, -1, 0});
  m.points.push_back({0, -1, 0.1});
  m.tris.push_back({8, 10, 9});
  m.surface.push_back(0);
  ShadowMapStats below;
  const ShadowMap c = build(true, &below);
  EXPECT_EQ(below.casters_culled, 1u);  // only the lowest triangle: everything is on its light side
  EXPECT_EQ(below.casters, 4u);
  EXPECT_EQ(c.lit_count({2.5, -1, 2.5}, up), 0u);  // under the ground, off the occluder's shadow
}

// A ground plane running behind a perspective eye just above it: near
// clipping keeps exactly the pixels whose rays meet the plane in the square.
TEST(Surfaces, NearClippedGroundCoversExactlyItsPixels) {
  TriangleMesh m;
  m.points = {{-50, 0, -50}, {50, 0, -50}, {50, 0, 50}, {-50, 0, 50}};
  m.tris = {{0, 2, 1}, {0, 3, 2}};
  m.surface = {0, 0};
  compute_point_normals(m);
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {0.3, 0.5, 0.2};
  cam.target = {0.3, -0.2, -2};
  cam.fov_y = 80;
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
  TriangleMesh m = cube();
  TriangleMesh ground;
  ground.points = {{-3, 0, -3}, {4, 0, -3}, {4, 0, 4}, {-3, 0, 4}};
  ground.tris = {{0, 2, 1}, {0, 3, 2}};
  for (glm::dvec3& p : m.points) p += glm::dvec3(0, 0.3, 0);
  append_mesh(m, ground, 1);
  compute_point_normals(m);
  return m;
}
Camera cube_camera() {
  Camera cam;
  cam.projection = Projection::Perspective;
  cam.eye = {3, 4, 5};
  cam.target = {0.5, 0.3, 0.5};
  cam.fov_y = 45;
  return cam;
}

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
