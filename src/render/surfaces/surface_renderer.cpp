#include "render/surfaces/surface_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>

#include "raster/depth_buffer.h"
#include "raster/tile_loop.h"
#include "raster/triangle_bins.h"
#include "raster/zbuffer_tile.h"
#include "lighting/map_lookup.h"
#include "lighting/shadow_rays.h"
#include "render/surfaces/rgba_store.h"
#include "render/surfaces/shade_batch.h"
#include "lighting/visible_region.h"
#include "base/util/memory.h"
#include "base/util/memory_ledger.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct TileState {
  DepthBuffer db;
  ShadeBatch batch;
  std::vector<float> lit;  // lights × kShadeBatch
  ZBufferScratch scratch;
  std::vector<float> out;
  SurfaceTileTotals totals;
};

static_assert(kNoShade == kNoId, "the shading batch takes the z-buffer's ids as they are");

// Per-pixel state of a tile: depth (8) + id (4) + the output floats.
constexpr uint64_t kTilePixelBytes = 12;

// Each triangle's part of a directional map's bias: ShadowMap::face_bias of
// its face normal towards the light (NaN: turned from it).
std::vector<double> face_biases(const ShadowMap& map, const Light& light, const std::vector<TriangleShade>& shades) {
  const glm::dvec3 to = to_light(light, glm::dvec3(0.0));
  std::vector<double> bias(shades.size());
  for (size_t t = 0; t < shades.size(); ++t) {
    const double* g = shades[t].g;
    bias[t] = map.face_bias((g[0] * to.x + g[1] * to.y) + g[2] * to.z);
  }
  return bias;
}

}  // namespace

std::vector<std::string> surface_channel_names(size_t lights) {
  std::vector<std::string> n = {"R", "G", "B", "A", "Z"};
  for (size_t l = 0; l < lights; ++l) n.push_back("lit" + std::to_string(l));
  return n;
}

uint64_t triangle_mesh_bytes(const TriangleMesh& m) {
  return m.points.size() * sizeof(glm::dvec3) * 2 + m.tris.size() * (sizeof(m.tris[0]) + 4);
}

struct SurfaceRenderer::Impl {
  const TriangleMesh& mesh;
  const SurfaceRenderSettings& rs;
  View view;
  TileGrid grid;
  ProjectedTriangles pt;
  std::vector<TriangleShade> shades;  // per projected triangle
  TriangleBins bins;
  std::vector<ShadowMap> maps;
  std::vector<MapLookup> lookups;          // per light (directional maps)
  std::vector<std::vector<float>> facing;  // per light (directional ones), per projected triangle
  std::unique_ptr<ShadowRays> rays;
  bool shadows = false;
  SurfaceStats setup;
  SurfaceTileTotals totals;
  tbb::enumerable_thread_specific<TileState> states;
  float bg[4] = {0, 0, 0, 0};  // the background's premultiplied RGBA
  bool any_spot = false;

  Impl(const TriangleMesh& m, const SurfaceRenderSettings& settings, uint64_t extra_bytes)
      : mesh(m), rs(settings), view(settings.camera, settings.width, settings.height) {
    const auto t_start = Clock::now();
    validate();
    const int threads = std::max(1, rs.threads);
    setup.memory_budget_bytes = rs.budget();
    setup.tile_size = rs.tile_size;
    shadows = rs.shadows_enabled && !rs.lights.empty();
    hold_memory(extra_bytes, threads);
    const Bounds scene = triangle_bounds(mesh);
    const double z_near = near_plane(scene);
    project(z_near, threads);
    set_up_lights(scene, z_near, threads);
    for (int c = 0; c < 4; ++c) bg[c] = float(rs.background[c]);
    setup.ms_setup = ms_since(t_start);
  }

  // The settings and mesh a render cannot start without; the tile grid.
  void validate() {
    if (rs.width == 0 || rs.height == 0) throw std::runtime_error("image size must be at least 1x1");
    if (rs.tile_size < 1) throw std::runtime_error("tile size must be at least 1 pixel");
    if (mesh.normals.size() != mesh.points.size()) throw std::runtime_error("surface renderer: point normals missing");
    for (uint32_t s : mesh.surface)
      if (s >= rs.colors.size()) throw std::runtime_error("surface renderer: a triangle's surface has no colour");
    grid = TileGrid{rs.width, rs.height, rs.tile_size, rs.depth_and_lit ? uint32_t(5 + rs.lights.size()) : 4u};
    if (uint64_t(grid.cols()) * grid.rows() >= (uint64_t(1) << 32))
      throw std::runtime_error("too many tiles; use a larger tile size");
  }

  // What the frame holds, against the budget: the caller's share, each
  // thread's tile (clipped to the image), the finished tiles queued for the
  // sink, the projected triangles, and the shadow maps or rays.
  void hold_memory(uint64_t extra_bytes, int threads) const {
    const uint64_t tile_px = grid.max_tile_pixels(), P = mesh.num_points(), T = mesh.num_tris();
    MemoryLedger ledger(rs.budget(), "a " + std::to_string(rs.width) + "x" + std::to_string(rs.height) +
                                         " render of " + std::to_string(T) + " triangles");
    ledger.add("what the caller holds", extra_bytes);
    ledger.add("each thread's tile", uint64_t(threads) * tile_px * (kTilePixelBytes + 4 * grid.channels));
    ledger.add("the tiles queued for output", relay_queue_tiles(grid, threads) * tile_px * 4 * grid.channels);
    // Projected vertices and corners, bins (estimate: each triangle in ~2 tiles).
    ledger.add("the projected triangles", P * sizeof(ScreenVertex) + T * (16 + 8 + sizeof(TriangleShade)));
    if (shadows && rs.shadows.mode != ShadowMode::Exact)
      ledger.add("its shadow maps", rs.lights.size() * shadow_map_bytes(rs.shadows) + P * sizeof(ScreenVertex),
                 "lower shadows.map_size");
    else if (shadows)
      ledger.add("its shadow rays' BVH", P * 12 + T * 12 * 3);  // vertex and index buffers, BVH
  }

  // A millionth of the scene in front of a perspective eye; orthographic
  // views keep depth >= 0 (the eye plane).
  double near_plane(const Bounds& scene) const {
    const double diag = std::max(scene.empty ? 1.0 : scene.diagonal(), 1e-300);
    return view.perspective() ? 1e-6 * (diag + glm::length(view.eye() - scene.centre())) : 0.0;
  }

  // The triangles in screen space, their shading set-ups, and the tile bins.
  void project(double z_near, int threads) {
    auto t = Clock::now();
    project_triangles(mesh, view, {rs.cull_back, rs.cull_view, z_near}, &pt, &setup.project);
    triangle_shades(mesh, pt.source, view, rs.shading.model, rs.colors, threads, &shades);
    setup.ms_project = ms_since(t);
    t = Clock::now();
    bin_triangles(grid, pt.verts, pt.corners, &bins);
    setup.bin_entries = bins.entries();
    setup.ms_binning = ms_since(t);
  }

  // The lights' shadow maps or rays, and what the shading reads per
  // triangle and light.
  void set_up_lights(const Bounds& scene, double z_near, int threads) {
    const auto t = Clock::now();
    if (shadows && rs.shadows.mode != ShadowMode::Exact)
      build_maps(scene, z_near, threads);
    else if (shadows) {
      rays = std::make_unique<ShadowRays>(mesh, threads);
      setup.ms_rays_build = rays->ms_build();
    }
    for (const Light& l : rs.lights) any_spot |= l.type == LightType::Spot;
    make_facing();
    if (!maps.empty()) make_lookups();
    setup.ms_shadows = ms_since(t);
  }

  // One shadow map per light, each fitted to what it must cover: for a
  // directional light, the points of the visible region (visible_region.h).
  void build_maps(const Bounds& scene, double z_near, int threads) {
    std::vector<LightFit> fits;
    for (const Light& l : rs.lights) fits.push_back(start_fit(l));
    const auto t_fit = Clock::now();
    bool any_directional = false;
    for (const Light& l : rs.lights) any_directional |= l.type == LightType::Directional;
    if (any_directional)
      visible_region_points(mesh, view, z_near, rs.cull_back, [&](const glm::dvec3& p) {
        for (LightFit& f : fits) f.add(p);
      });
    setup.ms_fit = ms_since(t_fit);
    for (size_t l = 0; l < rs.lights.size(); ++l) {
      ShadowMapStats ms;
      maps.push_back(ShadowMap::build(mesh, rs.lights[l], fits[l], scene, rs.shadows, threads, &ms));
      setup.maps.push_back(ms);
    }
  }

  // Directional lights: 1 where the face turns to the light, else 0. The
  // lit fraction without shadows, and in map tiles with no caster (the same
  // c > 0 as ShadowMap::face_bias's).
  void make_facing() {
    facing.resize(rs.lights.size());
    for (size_t l = 0; l < rs.lights.size(); ++l) {
      if (rs.lights[l].type != LightType::Directional) continue;
      const glm::dvec3 to = to_light(rs.lights[l], glm::dvec3(0.0));
      facing[l].resize(shades.size());
      for (size_t t = 0; t < shades.size(); ++t) {
        const double* g = shades[t].g;
        facing[l][t] = (g[0] * to.x + g[1] * to.y) + g[2] * to.z > 0 ? 1.f : 0.f;
      }
    }
  }

  // The directional maps' lookups from the pixels' camera-plane coordinates
  // (lighting/map_lookup.h), with each triangle's face bias.
  void make_lookups() {
    lookups.resize(maps.size());
    for (size_t l = 0; l < maps.size(); ++l)
      if (rs.lights[l].type == LightType::Directional)
        lookups[l] = map_lookup(view, maps[l], face_biases(maps[l], rs.lights[l], shades));
  }

  // One tile: z-buffer, then each covered pixel resolved once, a row (up to
  // kShadeBatch pixels of it) at a time.
  const float* render_tile(uint32_t tile, const TileRect& r) {
    const auto t0 = Clock::now();
    TileState& w = states.local();
    const uint32_t tw = r.width(), th = r.height(), C = grid.channels;
    w.db.reset(tw, th);
    const Viewport vp{int(r.x0), int(r.y0), int(r.x1), int(r.y1)};
    ZBufferCounts zc;
    zbuffer_triangles(pt.verts, pt.corners, bins.begin(tile), size_t(bins.end(tile) - bins.begin(tile)),
                      pt.perspective, vp, w.db, w.scratch, &zc);
    SurfaceTileTotals& T = w.totals;
    T.tiles += 1;
    T.triangles_scanned += zc.triangles;
    T.fragments += zc.fragments;
    T.depth_writes += zc.depth_writes;
    w.out.resize(size_t(tw) * th * C);
    const size_t L = rs.lights.size();
    ShadeBatch& b = w.batch;
    b.points = rays != nullptr || any_spot;
    w.lit.resize(std::max<size_t>(1, L) * kShadeBatch);
    for (uint32_t y = 0; y < th; ++y)
      for (uint32_t x0 = 0; x0 < tw; x0 += kShadeBatch) {
        // A run of up to kShadeBatch pixels of row y: the batch is the row's
        // ids and depths as they are (the background included), so no pass
        // gathers covered pixels and the output is written in order.
        const size_t p0 = size_t(y) * tw + x0;
        const int n = int(std::min<uint32_t>(kShadeBatch, tw - x0));
        const uint32_t* ids = w.db.front_ids() + p0;
        const double* zs = w.db.front_depths() + p0;
        b.n = n;
        b.Y = double(r.y0 + y);
        int covered = 0;
        for (int i = 0; i < n; ++i) {
          b.X[i] = double(r.x0 + x0 + uint32_t(i));
          b.id[i] = ids[i];
          b.tri[i] = ids[i] == kNoShade ? 0u : ids[i];
          b.zbuf[i] = zs[i];
          covered += ids[i] != kNoShade;
        }
        float* o = w.out.data() + p0 * C;
        if (covered == 0)
          write_background(n, C, o);
        else
          shade(w, T, L, covered, o);
      }
    T.ms_tiles += ms_since(t0);
    return w.out.data();
  }

  void write_background(int n, uint32_t C, float* o) const {
    for (int i = 0; i < n; ++i, o += C) {
      for (int c = 0; c < 4; ++c) o[c] = bg[c];
      for (uint32_t c = 4; c < C; ++c) o[c] = INFINITY;
    }
  }

  // The batch's pixels (`covered` of them have a triangle): hits and normals,
  // each light's lit fraction (map lookups, shadow rays, or only the cone and
  // facing), Blinn–Phong; written to `o` (the row's first pixel).
  void shade(TileState& w, SurfaceTileTotals& T, size_t L, int covered, float* o) const {
    ShadeBatch& b = w.batch;
    const int n = b.n;
    const uint32_t C = grid.channels;
    surface_hits(view, shades.data(), b);
    T.rendered_pixels += uint64_t(covered);
    float* lits = w.lit.data();  // L × kShadeBatch
    for (size_t l = 0; l < L; ++l) {
      const Light& light = rs.lights[l];
      float* lit = lits + l * kShadeBatch;
      if (shadows && rays) {
        for (int i = 0; i < n; ++i) {
          const double* g = shades[b.tri[i]].g;
          lit[i] = b.id[i] != kNoShade && rays->lit(light, {b.px[i], b.py[i], b.pz[i]}, {g[0], g[1], g[2]}) ? 1.f : 0.f;
        }
        T.shadow_rays += uint64_t(covered);
      } else if (shadows && light.type == LightType::Directional && rs.empty_tile_early_out &&
                 in_empty_tiles(l, b)) {
        // Every test passes: lit 1, or 0 where the face turns from the light.
        facing_of(facing[l].data(), b.tri, n, lit);
        T.shadow_tests += uint64_t(covered);
        T.shadow_tests_empty += uint64_t(covered);
      } else if (shadows) {
        uint32_t cnt[kShadeBatch];
        if (light.type == LightType::Directional)
          directional_counts(l, b, cnt);
        else {
          double gx[kShadeBatch], gy[kShadeBatch], gz[kShadeBatch];
          for (int i = 0; i < n; ++i) {
            const double* g = shades[b.tri[i]].g;
            gx[i] = g[0], gy[i] = g[1], gz[i] = g[2];
          }
          maps[l].lit_counts(size_t(n), b.px, b.py, b.pz, gx, gy, gz, cnt);
        }
        const float levels = float(maps[l].levels());
        for (int i = 0; i < n; ++i) lit[i] = float(cnt[i]) / levels;  // all levels: exactly 1
        T.shadow_tests += uint64_t(covered);
      } else if (light.type == LightType::Directional) {
        facing_of(facing[l].data(), b.tri, n, lit);  // per triangle: a float, not three doubles
      } else {
        for (int i = 0; i < n; ++i) {
          const double* g = shades[b.tri[i]].g;
          const glm::dvec3 p(b.px[i], b.py[i], b.pz[i]);
          lit[i] = b.id[i] != kNoShade && in_light_cone(light, p) &&
                           glm::dot(glm::dvec3(g[0], g[1], g[2]), to_light(light, p)) > 0
                       ? 1.f
                       : 0.f;
        }
      }
      for (int i = 0; i < n; ++i) T.lit_pixels += (lit[i] > 0) & (b.id[i] != kNoShade);
      add_lights(rs.shading, light, lit, b);
    }
    float rgb[3][kShadeBatch];
    surface_colours(b, rs.shading.ambient, rgb);
    if (C == 4)
      store_rgba(n, rgb[0], rgb[1], rgb[2], b.id, kNoShade, bg, o);
    else if (C == 6)
      write_pixels<6>(b, rgb, lits, bg, C, o);
    else
      write_pixels<0>(b, rgb, lits, bg, C, o);
  }

  // lit[i] = f[tri[i]]: with the pointers restrict, a vector gather (the
  // loop inline in shade stayed scalar: lit and f could alias).
  static void facing_of(const float* __restrict f, const uint32_t* __restrict tri, int n, float* __restrict lit) {
    for (int i = 0; i < n; ++i) lit[i] = f[tri[i]];
  }

  // The output of the batch's pixels, in order: colour, alpha 1, depth and
  // each light's lit fraction, or the background (depth and lit +inf).
  // Kc = C when known at compile time (one light: the channel loop unrolls).
  template <uint32_t Kc>
  static void write_pixels(const ShadeBatch& b, const float (*rgb)[kShadeBatch], const float* lits, const float* bg,
                           uint32_t Cr, float* __restrict o) {
    const uint32_t C = Kc ? Kc : Cr;
    const int n = b.n;
    for (int i = 0; i < n; ++i) {
      const bool none = b.id[i] == kNoShade;
      float* q = o + size_t(i) * C;
      q[0] = none ? bg[0] : rgb[0][i];
      q[1] = none ? bg[1] : rgb[1][i];
      q[2] = none ? bg[2] : rgb[2][i];
      q[3] = none ? bg[3] : 1.f;
      q[4] = none ? INFINITY : float(b.depth[i]);
      for (uint32_t c = 5; c < C; ++c) q[c] = none ? INFINITY : lits[size_t(c - 5) * kShadeBatch + i];
    }
  }

  // An exact early out for light l (a directional map): true when every
  // covered pixel's kernel falls in map tiles with no caster, so that every
  // test passes (none where the face turns from the light: a NaN limit). The
  // batch's range of X and Y has a texel of margin for the rounding of each
  // pixel's own inputs.
  bool in_empty_tiles(size_t l, const ShadeBatch& b) const {
    double s0, s1;
    depth_range(b, &s0, &s1);
    if (!(s0 <= s1)) return false;
    // The a of the batch's first and last pixel, as hit_run has them.
    const double isx = 1.0 / view.scale_x(), ox = view.offset_x();
    const double a0 = (b.X[0] - ox) * isx, a1 = (b.X[b.n - 1] - ox) * isx;
    double x[2], y[2], z[2];
    map_range(lookups[l], view.perspective(), std::min(a0, a1), std::max(a0, a1), b.cb, s0, s1, x, y, z);
    return std::abs(z[0]) < 1e300 && std::abs(z[1]) < 1e300 &&
           maps[l].passes_all(x[0] - 1, x[1] + 1, y[0] - 1, y[1] + 1);
  }

  // Light l's lit counts (a directional map) from the pixels' camera-plane
  // coordinates and depths.
  void directional_counts(size_t l, const ShadeBatch& b, uint32_t* cnt) const {
    double X[kShadeBatch], Y[kShadeBatch], lim[kShadeBatch];
    map_inputs(lookups[l], view.perspective(), b.n, b.ca, b.cb, b.depth, b.tri, X, Y, lim);
    maps[l].counts_at(size_t(b.n), X, Y, lim, cnt);
  }
};

SurfaceRenderer::SurfaceRenderer(const TriangleMesh& mesh, const SurfaceRenderSettings& settings, uint64_t extra_bytes)
    : impl_(std::make_unique<Impl>(mesh, settings, extra_bytes)) {}
SurfaceRenderer::~SurfaceRenderer() = default;
const TileGrid& SurfaceRenderer::grid() const { return impl_->grid; }
int SurfaceRenderer::threads() const { return std::max(1, impl_->rs.threads); }

void SurfaceRenderer::render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) {
  Impl& I = *impl_;
  const auto t0 = Clock::now();
  for (TileState& s : I.states) s.totals = {};
  run_tiles(I.grid, tiles ? *tiles : all_tiles(I.grid), threads(), sink,
            [&](uint32_t t, const TileRect& r) { return I.render_tile(t, r); });
  for (const TileState& s : I.states) I.totals += s.totals;
  I.setup.ms_total += ms_since(t0);
}

std::vector<uint8_t> SurfaceRenderer::tile_totals() const { return pod_bytes(impl_->totals); }
void SurfaceRenderer::add_tile_totals(const std::vector<uint8_t>& other) {
  SurfaceTileTotals t;
  if (!pod_from_bytes(other, &t)) throw std::runtime_error("surface renderer: tile totals of another kind");
  impl_->totals += t;
}

SurfaceStats SurfaceRenderer::stats() const {
  SurfaceStats s = impl_->setup;
  s.tiles = impl_->totals;
  s.ms_total += s.ms_setup;
  s.peak_rss_bytes = peak_rss_bytes();
  return s;
}

}  // namespace zs
