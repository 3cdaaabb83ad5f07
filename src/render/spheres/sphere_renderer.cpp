#include "render/spheres/sphere_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "raster/depth_buffer.h"
#include "raster/sphere_span.h"
#include "raster/tile_loop.h"
#include "lighting/ao_directions.h"
#include "lighting/sphere_map.h"
#include "lighting/shading_model.h"
#include "render/spheres/sphere_ao.h"
#include "render/spheres/sphere_bins.h"
#include "render/spheres/translucent_tile.h"
#include "base/util/bytes_str.h"
#include "base/util/memory.h"
#include "base/util/memory_ledger.h"
#include "base/util/progress.h"
#include "base/view/camera.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// A thread's scratch, reused from tile to tile.
// Pixels per side of the blocks whose farthest depth a tile keeps.
constexpr int kBlock = 8;
// Spheres whose box spans at least this many blocks get per-block depth bounds.
constexpr int kBoundBlocks = 4;
// Bin entries fetched ahead of the one being drawn.
constexpr uint64_t kPrefetch = 8;

struct alignas(128) TileState {
  DepthBuffer depth;
  // Per kBlock² block of the tile: the farthest depth in it, kept lazily
  // (recomputed when a test needs a block written since). A sphere whose
  // nearest depth lies behind every block under its box is skipped whole.
  std::vector<double> bmax;
  std::vector<uint8_t> bdirty;
  std::vector<double> zlow;  // per block of the current sphere's box: its depth bound there (+inf: hidden)
  FaceSpans spans;
  std::vector<float> out;  // RGBA + Z per pixel
  // The tile's visible pixels for shading and AO: pixel index, colour before
  // AO, world position and normal, and the AO sums.
  std::vector<uint32_t> vpix;
  std::vector<double> vrgb;  // colour and depth, 4 per visible pixel
  AoPoints aop;
  SphereStats stats;       // this thread's per-tile counts
  std::unique_ptr<TranslucentTile> translucent;  // the translucent modes' scratch
};

// Per-pixel bytes of a tile in flight: depth and id, output.
constexpr uint64_t kTilePixelBytes = 12;  // depth and id; plus 4 per output channel

}  // namespace

uint32_t sphere_channels(const SphereRenderSettings& rs) { return rs.ao.directions ? 6 : 5; }

uint64_t sphere_set_bytes(const SphereSet& s) {
  return s.centres.size() * sizeof(glm::dvec3) + s.radii.size() * 8 + s.scalars.size() * 8 +
         s.rgba.size() * sizeof(glm::vec4) + s.element.size();
}

struct SphereRenderer::Impl {
  const SphereSet& s;
  const std::vector<glm::vec4>& colors;
  const SphereGrid& g;
  const SphereRenderSettings& rs;
  View view;
  CameraPlane cam;
  TileGrid grid;
  SphereStats setup, totals;
  SphereBins bins;
  tbb::enumerable_thread_specific<TileState> states;
  uint64_t kbuf_bytes = 0;
  static constexpr uint64_t kMaxKbufBytes = uint64_t(512) << 20;
  // Ambient occlusion: the directions and one map each (null: off, or
  // batches: ao_batch maps at a time, built by every render_tiles(), their
  // sums per image pixel in ao_num).
  std::shared_ptr<const SphereAoMaps> ao;
  std::vector<glm::dvec3> ao_dirs;
  uint32_t ao_batch = 0;
  uint64_t ao_budget_left = 0;
  std::vector<double> ao_num;
  double ms_ao_batches = 0;
  uint64_t ao_batch_bytes = 0;

  Impl(const SphereSet& spheres, const std::vector<glm::vec4>& c, const SphereGrid& grid_, const SphereRenderSettings& settings,
       uint64_t extra_bytes, std::shared_ptr<const SphereAoMaps> ao_maps)
      : s(spheres), colors(c), g(grid_), rs(settings), view(settings.camera, settings.width, settings.height),
        cam(camera_plane(view)), ao(std::move(ao_maps)) {
    const auto t_start = Clock::now();
    validate();
    const int threads = std::max(1, rs.threads);
    MemoryLedger ledger(rs.budget(), "a " + std::to_string(rs.width) + "x" + std::to_string(rs.height) +
                                         " render of " + std::to_string(s.size()) + " spheres");
    start_stats(ledger);
    hold_frame(ledger, extra_bytes, threads);
    ledger.check("the visible list", s.size() * 4);
    std::vector<uint8_t> occluder;
    if (rs.mode != SphereMode::Opaque) occluder = occluders(ledger, threads);
    const std::vector<uint32_t> visible = visible_entries(std::move(occluder), ledger, threads);
    const auto t_bin = Clock::now();
    bins = bin_spheres(g, visible, view, grid, threads, ledger);
    setup.bin_entries = bins.ids.size();
    setup.ms_binning = ms_since(t_bin);
    // AO last: its maps (or batches) take what the view's own set-up leaves,
    // so maps that fit never leave the visible list or the bins without room.
    if (rs.ao.directions) choose_ao(ledger, threads);
    setup.shared_bytes = ledger.held();
    // What is left of the budget, per thread, for sorted's deeper k-buffer
    // passes (TranslucentTile::sorted), at most kMaxKbufBytes: enough for a
    // 64² tile 8192 fragments deep.
    const uint64_t base_kbuf = grid.max_tile_pixels() * TranslucentTile::kSortedLayers * 16;
    kbuf_bytes = std::max(base_kbuf, std::min(kMaxKbufBytes, ledger.left() / threads));
    setup.ms_setup = ms_since(t_start);
  }

  // The settings a render cannot start without; the tile grid.
  void validate() {
    if (rs.width == 0 || rs.height == 0) throw std::runtime_error("image size must be at least 1x1");
    if (rs.tile_size < 1) throw std::runtime_error("tile size must be at least 1 pixel");
    if (colors.size() != s.size()) throw std::runtime_error("one colour per sphere is needed");
    grid = TileGrid{rs.width, rs.height, rs.tile_size, sphere_channels(rs)};
    if (uint64_t(grid.cols()) * grid.rows() >= (uint64_t(1) << 32))
      throw std::runtime_error("too many tiles; use a larger tile size");
  }

  // The set-up's counts known before any work.
  void start_stats(const MemoryLedger& ledger) {
    setup.memory_budget_bytes = ledger.budget();
    setup.spheres = s.size();
    setup.invalid = g.invalid;
    setup.tiles = grid.count();
    setup.tile_size = rs.tile_size;
  }

  // What every frame holds: the caller's share, the grid, each thread's tile
  // (clipped to the image) and the finished tiles queued for the sink.
  void hold_frame(MemoryLedger& ledger, uint64_t extra_bytes, int threads) const {
    const uint64_t tile_px = grid.max_tile_pixels();
    ledger.add("what the caller holds", extra_bytes);
    ledger.add("the sphere grid", g.bytes());
    ledger.add("each thread's tile", uint64_t(threads) * tile_px * (kTilePixelBytes + 4 * grid.channels));
    ledger.add("the tiles queued for output", relay_queue_tiles(grid, threads) * tile_px * 4 * grid.channels);
  }

  // AO (spheres digest §2.4.5): every direction's map held (the caller's,
  // or built here when they all fit what is left), else batches of maps
  // built by every frame, with the image's sums (sphere_ao.h).
  void choose_ao(MemoryLedger& ledger, int threads) {
    ao_dirs = ao_directions(rs.ao.directions);
    // The caller's maps were sized before this frame's own holdings: where
    // they no longer fit, an opaque frame builds them in batches instead
    // (the stats say so; the caller then lets its maps go).
    if (ao && ao->bytes > ledger.left() && rs.mode == SphereMode::Opaque) ao.reset();
    if (!ao && !rs.ao.batches) {
      ao = sphere_ao_maps(s, colors, rs, ledger.left());  // null: they do not all fit
      if (ao) setup.ms_ao_maps = ao->ms_build;
    }
    if (ao) {
      setup.ao_map_bytes = ao->bytes;
      setup.ao_translucent_fragments = ao->translucent_fragments;
      ledger.add("the AO maps", ao->bytes, "lower ao.map_size");
      return;
    }
    const uint64_t sums = sphere_ao_sums_bytes(rs);
    ao_batch = sphere_ao_batch_size(rs, ledger.budget(), ledger.held(), threads);
    setup.ao_batches = (rs.ao.directions + ao_batch - 1) / ao_batch;
    ao_budget_left = ledger.left() - sums;  // what a batch may really take
    ledger.add("the AO sums and a batch of maps", sums + uint64_t(ao_batch) * sphere_ao_map_bytes_bound(rs),
               "lower ao.map_size");
  }

  // Translucent modes: only opaque spheres hide others (culling stays
  // lossless), one flag per grid entry; and each thread holds a tile's
  // translucent state.
  std::vector<uint8_t> occluders(MemoryLedger& ledger, int threads) const {
    std::vector<uint8_t> occluder(g.ids.size());
    for (size_t e = 0; e < g.ids.size(); ++e) occluder[e] = colors[g.ids[e]].a >= 1.f;
    ledger.add("the translucent tiles",
               occluder.size() + uint64_t(threads) * grid.max_tile_pixels() * TranslucentTile::kPixelBytes);
    return occluder;
  }

  // The grid entries the frame draws (sphere_visibility.h; `occluder`: the
  // translucent modes' flags, else empty); alpha 0 draws nothing in a
  // translucent mode.
  std::vector<uint32_t> visible_entries(std::vector<uint8_t> occluder, MemoryLedger& ledger, int threads) {
    const auto t_vis = Clock::now();
    std::vector<uint32_t> visible = visible_spheres(s, g, view, rs.culling, &setup.vis, threads,
                                                    occluder.empty() ? nullptr : &occluder);
    occluder = {};
    if (rs.mode != SphereMode::Opaque) {
      const size_t before = visible.size();
      visible.erase(std::remove_if(visible.begin(), visible.end(), [&](uint32_t e) { return !(colors[g.ids[e]].a > 0.f); }),
                    visible.end());
      setup.spheres_clear = before - visible.size();
    }
    setup.ms_visibility = ms_since(t_vis);
    ledger.add("the visible list", visible.size() * 4 + setup.vis.map_bytes);
    return visible;
  }

  // Whether every block of the tile under pixel box [i0, i1] x [j0, j1] (tile
  // coordinates) is nearer than z everywhere.
  static bool blocks_nearer(TileState& ts, uint32_t w, uint32_t h, int i0, int i1, int j0, int j1, double z) {
    for (int by = j0 / kBlock; by <= j1 / kBlock; ++by)
      for (int bx = i0 / kBlock; bx <= i1 / kBlock; ++bx)
        if (!(block_far(ts, w, h, bx, by) < z)) return false;
    return true;
  }

  // The farthest depth in block (bx, by) of the tile, recomputed when written since.
  static double block_far(TileState& ts, uint32_t w, uint32_t h, int bx, int by) {
    const uint32_t bw = (w + kBlock - 1) / kBlock;
    const size_t b = size_t(by) * bw + size_t(bx);
    if (ts.bdirty[b]) {
      double m = -INFINITY;
      const uint32_t y1 = std::min<uint32_t>(h, uint32_t(by + 1) * kBlock);
      const uint32_t x1 = std::min<uint32_t>(w, uint32_t(bx + 1) * kBlock);
      for (uint32_t y = uint32_t(by) * kBlock; y < y1; ++y)
        for (uint32_t x = uint32_t(bx) * kBlock; x < x1; ++x) m = std::max(m, ts.depth.depth(size_t(y) * w + x));
      ts.bmax[b] = m;
      ts.bdirty[b] = 0;
    }
    return ts.bmax[b];
  }

  // A sphere wrote into these pixels: their blocks' farthest depths may have moved.
  static void mark_blocks(TileState& ts, uint32_t bw, int i0, int i1, int j0, int j1) {
    for (int by = j0 / kBlock; by <= j1 / kBlock; ++by)
      for (int bx = i0 / kBlock; bx <= i1 / kBlock; ++bx) ts.bdirty[size_t(by) * bw + size_t(bx)] = 1;
  }

  // One tile: nearest (depth, id) per pixel, then shade each pixel once.
  const float* render_tile(uint32_t t, const TileRect& r) {
    TileState& ts = states.local();
    SphereStats& S = ts.stats;
    if (rs.mode != SphereMode::Opaque) {
      if (!ts.translucent) ts.translucent = std::make_unique<TranslucentTile>();
      const TranslucentFrame f{&s, &g, &colors, &rs, &view, cam, kbuf_bytes, ao.get()};
      return ts.translucent->render(f, bins.ids.data() + bins.offset[t], bins.offset[t + 1] - bins.offset[t], r, S);
    }
    raster(ts, t, r);
    resolve(ts, r);
    return ts.out.data();
  }

  // The opaque depth pass: nearest (depth, id) per pixel of the tile.
  void raster(TileState& ts, uint32_t t, const TileRect& r) {
    SphereStats& S = ts.stats;
    const uint32_t w = r.width(), h = r.height();
    ts.depth.reset(w, h, 1);
    const uint32_t nb = ((w + kBlock - 1) / kBlock) * ((h + kBlock - 1) / kBlock);
    ts.bmax.assign(nb, INFINITY);
    ts.bdirty.assign(nb, 0);
    const uint32_t bw = (w + kBlock - 1) / kBlock;
    const Viewport vp{int(r.x0), int(r.y0), int(r.x1), int(r.y1)};
    const uint64_t e_end = bins.offset[t + 1];
    for (uint64_t e = bins.offset[t]; e < e_end; ++e) {
      // Bins are in depth order, so the entries are scattered in memory:
      // fetch a few ahead (most spheres end in a cheap test, and the loop
      // would otherwise wait on every centre).
      if (e + kPrefetch < e_end) {
        const uint32_t ahead = bins.ids[e + kPrefetch];
        __builtin_prefetch(&g.centre[ahead]);
        __builtin_prefetch(&g.radius[ahead]);
        __builtin_prefetch(&g.ids[ahead]);
      }
      const uint32_t entry = bins.ids[e], id = g.ids[entry];
      const glm::dvec3 c = to_camera(view, g.centre[entry]);
      const SphereSetup su = setup_sphere(cam, c.x, c.y, c.z, g.radius[entry]);
      // No surface of the sphere is nearer than this (a little below its
      // nearest depth, for rounding): a pixel already nearer cannot change.
      const double zmin = c.z - g.radius[entry];
      const double z_reject = zmin - 1e-9 * std::abs(zmin);
      int i0, i1, j0, j1;
      if (!sphere_pixel_range(su, vp, &i0, &i1, &j0, &j1)) continue;
      i0 -= vp.x0, i1 -= vp.x0, j0 -= vp.y0, j1 -= vp.y0;  // tile coordinates
      if (blocks_nearer(ts, w, h, i0, i1, j0, j1, z_reject)) {
        ++S.spheres_block_rejected;
        continue;
      }
      ++S.spheres_scanned;
      const uint64_t writes_before = S.depth_writes;
      if ((i1 - i0 + 1) * (j1 - j0 + 1) <= kSmallSphereBox) {
        // Small on screen: every pixel centre of the (conservative) box is
        // tried directly, cheaper than finding each row's run first; the
        // pixels hit are the same ones.
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i) {
            const size_t p = size_t(j) * w + size_t(i);
            if (ts.depth.depth(p) < z_reject) {
              ++S.early_rejected;
              continue;
            }
            ++S.pixel_tests;
            SphereHit hit;
            if (!sphere_hit(su, double(i + vp.x0), double(j + vp.y0), &hit)) continue;
            ++S.fragments;
            if (ts.depth.test_write(p, hit.t, id)) ++S.depth_writes;
          }
        if (S.depth_writes != writes_before) mark_blocks(ts, bw, i0, i1, j0, j1);
        continue;
      }
      // Per 8×8 block of its box, the nearest the sphere can be there
      // (sphere_depth_bound): a pixel already nearer skips its exact hit,
      // a block nearer everywhere is skipped whole. A large sphere's nearest
      // depth is far in front of most of its surface, so this rejects much
      // more than z_reject alone where spheres nest.
      const int bx0 = i0 / kBlock, by0 = j0 / kBlock, nbx = i1 / kBlock - bx0 + 1, nby = j1 / kBlock - by0 + 1;
      ts.zlow.resize(size_t(nbx) * size_t(nby));
      int row0 = nby, row1 = -1;  // the block rows not hidden whole
      if (nbx * nby < kBoundBlocks) {
        // Spanning few blocks: the bounds would gain little over z_reject
        // (already tested against every block above).
        std::fill(ts.zlow.begin(), ts.zlow.end(), z_reject);
        row0 = 0, row1 = nby - 1;
      }
      for (int by = 0; by < nby && nbx * nby >= kBoundBlocks; ++by)
        for (int bx = 0; bx < nbx; ++bx) {
          const int px = (bx0 + bx) * kBlock, py = (by0 + by) * kBlock;
          const double X0 = px + vp.x0, X1 = std::min<int>(px + kBlock, int(w)) - 1 + vp.x0;
          const double Y0 = py + vp.y0, Y1 = std::min<int>(py + kBlock, int(h)) - 1 + vp.y0;
          const double zl = std::max(z_reject, sphere_depth_bound(su, X0, X1, Y0, Y1));
          const bool hidden = block_far(ts, w, h, bx0 + bx, by0 + by) < zl;
          ts.zlow[size_t(by) * nbx + bx] = hidden ? INFINITY : zl;
          if (!hidden) row0 = std::min(row0, by), row1 = by;
        }
      if (row1 < 0) {
        ++S.spheres_block_rejected;
        --S.spheres_scanned;
        continue;
      }
      // Only the rows of those block rows are scanned (a run never leaves
      // its row, so the others could only give rejected pixels).
      const Viewport rows{vp.x0, vp.y0 + (by0 + row0) * kBlock, vp.x1,
                          std::min(vp.y1, vp.y0 + (by0 + row1 + 1) * kBlock)};
      ts.spans.clear();
      ScanCounters sc;
      scan_sphere(su, rows, ts.spans, sc);
      S.pixel_tests += sc.pixel_tests;
      for (const RowSpan& row : ts.spans.rows) {
        const int y = row.y - vp.y0;
        const size_t base = size_t(y) * w;
        const double* zrow = ts.zlow.data() + size_t(y / kBlock - by0) * nbx;
        // By block segments of the run (a run may step past the box: there,
        // the sphere's nearest depth only).
        for (int x = row.x0 - vp.x0, xe = row.x1 - vp.x0; x <= xe;) {
          const int b = x / kBlock - bx0, end = std::min(xe, (x / kBlock + 1) * kBlock - 1);
          const double zl = b >= 0 && b < nbx ? zrow[b] : z_reject;
          if (zl == INFINITY) {
            S.early_rejected += uint64_t(end - x + 1);
            x = end + 1;
            continue;
          }
          for (; x <= end; ++x) {
            const size_t p = base + size_t(x);
            if (ts.depth.depth(p) < zl) {
              ++S.early_rejected;
              continue;
            }
            SphereHit hit;
            if (!sphere_hit(su, double(x + vp.x0), double(row.y), &hit)) continue;
            ++S.fragments;
            if (ts.depth.test_write(p, hit.t, id)) ++S.depth_writes;
          }
        }
      }
      if (S.depth_writes != writes_before) mark_blocks(ts, bw, i0, i1, j0, j1);
    }
  }

  // The visible pixels of a rastered tile: their index, and their world
  // position and normal (with `colour`, also their shaded colour before AO).
  void gather(TileState& ts, const TileRect& r, bool colour) {
    const uint32_t w = r.width(), h = r.height();
    ts.vpix.clear(), ts.vrgb.clear();
    ts.aop.clear();
    // Neighbouring pixels mostly show the same sphere: its set-up is kept
    // while the id repeats (the same values, so the same image).
    uint32_t last = kNoId;
    glm::dvec3 c(0);
    double R = 1;
    SphereSetup su{};
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        const size_t p = size_t(y) * w + x;
        const uint32_t id = ts.depth.id(p);
        if (id == kNoId) continue;
        const double X = double(r.x0 + x), Y = double(r.y0 + y);
        if (id != last) {
          c = to_camera(view, s.centres[id]);
          R = s.radii[id];
          su = setup_sphere(cam, c.x, c.y, c.z, R);
          last = id;
        }
        SphereHit hit{0, 0, 0, false};
        sphere_hit(su, X, Y, &hit);  // the same call that won the depth test
        const double a = (X - cam.ox) / cam.sx, b = (cam.oy - Y) / cam.sy;
        const glm::dvec3 P = view.perspective() ? glm::dvec3(a * hit.t, b * hit.t, hit.t) : glm::dvec3(a, b, hit.t);
        glm::dvec3 n = (P - c) / R;
        if (hit.inside) n = -n;  // seen from inside: the surface faces the eye the other way
        // Camera space (x right, y up, z forward) to view space (z towards the viewer).
        n = glm::normalize(glm::dvec3(n.x, n.y, -n.z));
        ts.vpix.push_back(uint32_t(p));
        if (colour) {
          const glm::dvec3 v = view.perspective() ? glm::normalize(glm::dvec3(-P.x, -P.y, P.z)) : glm::dvec3(0, 0, 1);
          const glm::vec4& col = colors[id];
          const glm::dvec3 rgb = shade(rs.shading, glm::dvec3(col.r, col.g, col.b), n, v);
          ts.vrgb.insert(ts.vrgb.end(), {rgb.r, rgb.g, rgb.b, hit.t});
        }
        if (rs.ao.directions) {
          glm::dvec3 Pw, Nw;
          ao_world(view, P, n, &Pw, &Nw);
          ts.aop.add(size_t(r.y0 + y) * rs.width + (r.x0 + x), Pw, Nw);
        }
      }
  }

  // Shades each visible pixel once (deferred, spheres digest §2.4.6): its colour, then AO
  // over the tile's visible pixels direction by direction (the maps held, or
  // the sums the batches left in ao_num); colour = AO × shaded colour.
  void resolve(TileState& ts, const TileRect& r) {
    const uint32_t w = r.width(), h = r.height();
    const uint32_t C = grid.channels;
    ts.out.resize(size_t(w) * h * C);
    float* out = ts.out.data();
    const double* bg = rs.background;
    for (size_t p = 0; p < size_t(w) * h; ++p) {
      float* o = out + p * C;
      for (int k = 0; k < 4; ++k) o[k] = float(bg[k]);
      for (uint32_t k = 4; k < C; ++k) o[k] = INFINITY;
    }
    gather(ts, r, true);
    const size_t n = ts.vpix.size();
    if (rs.ao.directions) ao_sums(ts.aop, ao.get(), ao_dirs, ao_num);
    for (size_t i = 0; i < n; ++i) {
      float* o = out + size_t(ts.vpix[i]) * C;
      glm::dvec3 rgb(ts.vrgb[4 * i], ts.vrgb[4 * i + 1], ts.vrgb[4 * i + 2]);
      if (rs.ao.directions) {
        const double a = ts.aop.ao(i);
        rgb *= a;  // final colour = AO × shaded colour (spheres digest §2.4.6)
        o[5] = float(a);
      }
      o[0] = float(rgb.r), o[1] = float(rgb.g), o[2] = float(rgb.b), o[3] = 1.f;  // opaque: alpha ignored
      o[4] = float(ts.vrgb[4 * i + 3]);
    }
    ts.stats.rendered_pixels += n;
  }

  // Batches: per batch of directions, its maps, then every requested tile's
  // depth pass and the batch's terms added to ao_num (resolve() divides).
  void stream_ao(const std::vector<uint32_t>& tiles) {
    ao_num.assign(size_t(rs.width) * rs.height, 0.0);
    tbb::task_arena arena(std::max(1, rs.threads));
    for (size_t k0 = 0; k0 < ao_dirs.size(); k0 += ao_batch) {
      const std::vector<glm::dvec3> dirs(ao_dirs.begin() + k0,
                                         ao_dirs.begin() + std::min(ao_dirs.size(), k0 + ao_batch));
      const SphereAoMaps b = build_sphere_ao(s, colors, rs, dirs);
      ms_ao_batches += b.ms_build;
      ao_batch_bytes = std::max(ao_batch_bytes, b.bytes);
      if (b.bytes > ao_budget_left)
        throw std::runtime_error("memory budget of " + bytes_str(setup.memory_budget_bytes) + " cannot hold a batch of " +
                                 std::to_string(dirs.size()) + " AO maps with their translucent lists (" +
                                 bytes_str(b.bytes) + "); raise --memory-budget or lower ao.map_size");
      arena.execute([&] {
        tbb::parallel_for(size_t(0), tiles.size(), [&](size_t q) {
          const uint32_t t = tiles[q];
          const TileRect r = grid.rect(t);
          TileState& ts = states.local();
          SphereStats keep = ts.stats;  // the counts are the final pass's
          raster(ts, t, r);
          ts.stats = keep;
          gather(ts, r, false);
          add_ao_batch(ts.aop, b, ao_num);
        });
      });
    }
  }
};

SphereRenderer::SphereRenderer(const SphereSet& spheres, const std::vector<glm::vec4>& colors, const SphereGrid& grid,
                               const SphereRenderSettings& settings, uint64_t extra_bytes,
                               std::shared_ptr<const SphereAoMaps> ao_maps)
    : impl_(std::make_unique<Impl>(spheres, colors, grid, settings, extra_bytes, std::move(ao_maps))) {}
SphereRenderer::~SphereRenderer() = default;
const TileGrid& SphereRenderer::grid() const { return impl_->grid; }
int SphereRenderer::threads() const { return std::max(1, impl_->rs.threads); }

void SphereRenderer::render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) {
  Impl& I = *impl_;
  const auto t0 = Clock::now();
  std::vector<uint32_t> all;
  if (!tiles) {
    all = all_tiles(I.grid);
    tiles = &all;
  }
  uint64_t work = 0;
  for (uint32_t t : *tiles) work += I.bins.offset[t + 1] - I.bins.offset[t] + 1;
  Progress progress("render", work, I.rs.progress);
  for (TileState& ts : I.states) ts.stats = {};
  if (I.rs.ao.directions && !I.ao) I.stream_ao(*tiles);
  run_tiles(I.grid, *tiles, threads(), sink, [&](uint32_t t, const TileRect& r) {
    const float* px = I.render_tile(t, r);
    progress.add(I.bins.offset[t + 1] - I.bins.offset[t] + 1);
    return px;
  });
  progress.finish();
  for (const TileState& ts : I.states) add_tile_stats(I.totals, ts.stats);
  I.totals.ms_total += ms_since(t0);
  I.totals.peak_rss_bytes = std::max(I.totals.peak_rss_bytes, peak_rss_bytes());
}

std::vector<uint8_t> SphereRenderer::tile_totals() const { return pod_bytes(impl_->totals); }

void SphereRenderer::add_tile_totals(const std::vector<uint8_t>& other) {
  SphereStats o;
  if (!pod_from_bytes(other, &o)) throw std::runtime_error("sphere tile totals of the wrong size");
  add_tile_stats(impl_->totals, o);
  impl_->totals.ms_total += o.ms_total;
  impl_->totals.peak_rss_bytes = std::max(impl_->totals.peak_rss_bytes, o.peak_rss_bytes);
}

SphereStats SphereRenderer::stats() const {
  SphereStats s = impl_->setup;
  add_tile_stats(s, impl_->totals);
  if (impl_->rs.ao.directions && !impl_->ao) {  // batches: built by the frame
    s.ms_ao_maps = impl_->ms_ao_batches;
    s.ao_map_bytes = impl_->ao_batch_bytes;
  }
  s.ms_total = s.ms_setup + impl_->totals.ms_total;
  s.peak_rss_bytes = std::max(impl_->totals.peak_rss_bytes, peak_rss_bytes());
  return s;
}

const char* to_string(SphereMode m) {
  switch (m) {
    case SphereMode::Opaque: return "opaque";
    case SphereMode::Sorted: return "sorted";
    case SphereMode::Peel: return "peel";
    case SphereMode::DualPeel: return "dual_peel";
    case SphereMode::Weighted: return "weighted";
  }
  return "?";
}

bool parse_sphere_mode(const std::string& str, SphereMode* out) {
  for (SphereMode m : {SphereMode::Opaque, SphereMode::Sorted, SphereMode::Peel, SphereMode::DualPeel,
                       SphereMode::Weighted})
    if (str == to_string(m)) return *out = m, true;
  return false;
}

}  // namespace zs
