#include "render/volume/zsweep_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include "raster/image_sink.h"
#include "raster/tile_loop.h"
#include "base/util/memory.h"
#include "base/util/progress.h"
#include "render/volume/face_classes.h"
#include "render/volume/near_clip.h"
#include "render/volume/sweep_order.h"
#include "render/volume/tile_bins.h"
#include "base/util/bytes_str.h"
#include "render/volume/tile_sweep.h"

namespace zs {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

}  // namespace

void add_stats(RenderStats& a, const RenderStats& b) {
  a.ms_list_generation += b.ms_list_generation;
  a.ms_scan_convert += b.ms_scan_convert;
  a.ms_insert += b.ms_insert;
  a.ms_composite += b.ms_composite;
  a.pixel_tests += b.pixel_tests;
  a.pixel_hits += b.pixel_hits;
  a.pixel_misses += b.pixel_misses;
  a.fragments += b.fragments;
  a.rendered_pixels += b.rendered_pixels;
  a.faces_projected += b.faces_projected;
  a.faces_degenerate += b.faces_degenerate;
  a.max_list_length = std::max(a.max_list_length, b.max_list_length);
  a.forced_composites += b.forced_composites;
  a.budget_flushes += b.budget_flushes;
  a.composite_events += b.composite_events;
  a.segments += b.segments;
  a.segments_clipped += b.segments_clipped;
  a.rays_stopped += b.rays_stopped;
  a.early_terminated_pixels += b.early_terminated_pixels;
  a.peak_fragments = std::max(a.peak_fragments, b.peak_fragments);  // per tile
  a.peak_overflow_fragments = std::max(a.peak_overflow_fragments, b.peak_overflow_fragments);
  a.bconvert_fallbacks += b.bconvert_fallbacks;
  for (int k = 0; k < 4; ++k) a.row_end_misses[k] += b.row_end_misses[k];
  a.face_area += b.face_area;
  a.bbox_area += b.bbox_area;
}

constexpr uint64_t kMinPoolFragments = 256;

uint64_t zsweep_shared_bytes(size_t num_points, size_t num_faces) {
  // Per vertex: view position and, while the order is built, its event and
  // sort key (then its rank, plane depth and run starts). Per face: class,
  // sweep item and the order's 8-byte key, freed before the bins are made
  // (half of it here, half as check_memory_budget's 4 bytes a face). The
  // near-plane clip's flags (a byte per face and per tet) are not counted:
  // only views with vertices behind the eye need them.
  const uint64_t per_point = sizeof(ScreenVertex) + sizeof(SweepEvent) + sizeof(SweepKey) + 8;
  return num_points * per_point + num_faces * (1 + sizeof(SweepItem) + 4);
}

RenderPlan plan_render(uint64_t budget, uint64_t shared, uint64_t tile_pixels, int threads) {
  threads = std::max(1, threads);
  const uint64_t tile_state = tile_pixels * kTilePixelBytes;
  RenderPlan p;
  p.shared_bytes = shared;
  // Each thread's pool must hold at least a few fragments; the rest is
  // compositing early (budget flushes), which does not change the image.
  const uint64_t need = shared + uint64_t(threads) * (tile_state + kMinPoolFragments * sizeof(Fragment));
  if (need >= budget) return p;  // max_fragments = 0: the caller reports it
  p.max_fragments = (budget - shared - uint64_t(threads) * tile_state) / sizeof(Fragment) / uint64_t(threads);
  return p;
}

namespace {
std::runtime_error budget_too_small(const RenderSettings& rs, uint64_t budget, uint64_t need) {
  return std::runtime_error("memory budget of " + bytes_str(budget) + " cannot hold a " + std::to_string(rs.width) +
                            "x" + std::to_string(rs.height) + " render of this mesh (needs more than " +
                            bytes_str(need) + ")");
}
}  // namespace

uint64_t check_memory_budget(const TetMesh& mesh, const Topology& topo, const RenderSettings& rs, uint64_t sink_bytes) {
  if (rs.width == 0 || rs.height == 0) throw std::runtime_error("image size must be at least 1x1");
  if (rs.tile_size < 1) throw std::runtime_error("tile size must be at least 1 pixel");
  const int threads = std::max(1, rs.threads);
  const uint64_t budget = rs.budget();
  const TileGrid grid{rs.width, rs.height, rs.tile_size};
  // Tile ids are 32-bit; a grid that large would not fit any budget anyway.
  const uint64_t tiles = uint64_t(grid.cols()) * grid.rows();
  if (tiles >= (uint64_t(1) << 32))
    throw std::runtime_error(std::to_string(rs.width) + "x" + std::to_string(rs.height) + " in " +
                             std::to_string(rs.tile_size) + "-pixel tiles is too many tiles; use a larger tile size");
  // Vertices and faces, the sink, the relay's queue and the bins' per-tile
  // offsets; the bins' entries are known only later (one per face here).
  const uint64_t tile_px = grid.max_tile_pixels();
  const uint64_t shared = zsweep_shared_bytes(mesh.num_points(), topo.num_faces()) + sink_bytes +
                          relay_queue_tiles(grid, threads) * tile_px * 16 + (tiles + 1) * 8;
  const uint64_t need = shared + topo.num_faces() * 4;
  if (plan_render(budget, need, tile_px, threads).max_fragments == 0)
    throw budget_too_small(rs, budget, need + uint64_t(threads) * (tile_px * kTilePixelBytes + kMinPoolFragments * 16));
  return shared - (tiles + 1) * 8;  // the bins' offsets are counted again with their real size
}

struct ZSweepRenderer::Impl {
  const RenderSettings& rs;
  View view;
  SegmentIntegrator integ;
  SweepShared in;
  TileGrid grid;
  RenderPlan plan;
  RenderStats setup;
  RenderStats totals;  // per-tile parts of the render_tiles calls without a stats record
  // Per-thread scratch (records, pool, batch), kept across render_tiles
  // calls: MPI ranks call it once per run of tiles.
  tbb::enumerable_thread_specific<TileWorkspace> spaces;

  ViewBuffers* reuse;  // where the per-view arrays go back to, or null

  Impl(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings, uint64_t sink_bytes,
       ViewBuffers* buffers)
      : rs(settings), view(settings.camera, settings.width, settings.height), integ(settings.tf, settings.integrator),
        in{topo, settings, view, integ, {}, {}, {}, {}, {}, 0}, reuse(buffers) {
    const auto t_start = Clock::now();
    RenderStats& S = setup;
    // Checked before anything large is allocated, with the bins counted as
    // one entry per face; checked again once their real size is known.
    const uint64_t shared0 = check_memory_budget(mesh, topo, rs, sink_bytes);
    grid = TileGrid{rs.width, rs.height, rs.tile_size};
    const int threads = std::max(1, rs.threads);
    const uint64_t budget = rs.budget();
    S.memory_budget_bytes = budget;
    S.tile_size = rs.tile_size;
    S.tiles = grid.count();
    const uint64_t tile_state = grid.max_tile_pixels() * kTilePixelBytes;

    // The per-view set-up runs on the render's threads; none of its results
    // depends on how many.
    tbb::task_arena(threads).execute([&] { prepare(mesh, topo); });
    // The bins live in the order's key array (two words a face, freed in
    // the count above) when it is larger than they need.
    const uint64_t shared = shared0 - topo.num_faces() * 4 + in.bins.items.capacity() * 4 + in.bins.offset.size() * 8;
    plan = plan_render(budget, shared, grid.max_tile_pixels(), threads);
    if (plan.max_fragments == 0)
      throw budget_too_small(rs, budget, shared + uint64_t(threads) * (tile_state + kMinPoolFragments * 16));
    S.fragment_capacity = plan.max_fragments;
    S.ms_setup = ms_since(t_start);
  }

  ~Impl() {
    if (!reuse) return;
    reuse->sv = std::move(in.sv);
    reuse->cls = std::move(in.cls);
    reuse->items = std::move(in.items.items);
    reuse->words = std::move(in.bins.items);
  }

  // View, classes, near-plane clip, sweep order and bins (in.*, setup.*).
  void prepare(const TetMesh& mesh, const Topology& topo) {
    RenderStats& S = setup;
    const size_t nv = mesh.num_points();
    ViewBuffers given;
    if (reuse) std::swap(given, *reuse);
    in.sv = std::move(given.sv);
    in.sv.resize(nv);
    const double zmin = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(0, uint32_t(nv), 1 << 14), double(INFINITY),
        [&](const tbb::blocked_range<uint32_t>& r, double z) {
          for (uint32_t v = r.begin(); v < r.end(); ++v) {
            const ViewPoint p = view.project(mesh.points[v]);
            in.sv[v] = {p.x, p.y, p.z, mesh.has_scalars() ? mesh.scalars[v] : 0.0, v};
            if (p.z > 0) z = std::min(z, p.z);
          }
          return z;
        },
        [](double a, double b) { return std::min(a, b); });
    // Fragments store depth relative to the nearest vertex, as float: keeps
    // their precision when the camera is far from the mesh.
    in.z_origin = std::isfinite(zmin) ? zmin : 0.0;
    in.cell = mesh.has_cell_scalars() ? mesh.cell_scalars.data() : nullptr;

    // Perspective rays start at the eye: keep a tiny positive near distance so
    // that projecting never divides by zero. Orthographic rays start on the eye plane.
    const double z_near = view.perspective() ? 1e-7 * std::max(bounds_of(mesh).diagonal(), 1e-300) : 0.0;
    const bool clip = std::any_of(in.sv.begin(), in.sv.end(), [&](const ScreenVertex& v) { return !(v.z > z_near); });
    FaceClassCounts fc;
    std::vector<uint8_t> tet_visible;  // only the near-plane clip needs it
    std::vector<uint8_t> on_face;  // per point: on a face that is not culled
    in.cls = classify_faces(mesh, topo, rs.tf, view, &fc, clip ? &tet_visible : nullptr, &on_face, std::move(given.cls),
                            &rs.clip);
    std::vector<uint8_t> clipped;  // empty: nothing clipped
    if (clip) {
      clipped.assign(topo.num_faces(), 0);
      clip_at_near_plane(mesh, topo, view, in.sv, in.cls, tet_visible, z_near, &in.near, &clipped);
      S.faces_clipped = uint64_t(std::count(clipped.begin(), clipped.end(), 1));
    }
    std::vector<uint8_t>().swap(tet_visible);
    S.tets_invisible = fc.tets_invisible;
    S.tets_degenerate = fc.tets_degenerate;
    S.faces_culled = fc.faces_culled;
    S.cell_data_tets = fc.cell_data_tets;
    S.tets_clipped = fc.tets_clipped;
    // The sweep's events: vertices in front of the near plane on a face that
    // is not culled.
    std::vector<SweepEvent> events;
    for (uint32_t v = 0; v < nv; ++v)
      if (on_face[v] && in.sv[v].z > z_near && std::isfinite(in.sv[v].z)) events.push_back({in.sv[v].z, v});
    std::vector<uint8_t>().swap(on_face);
    const auto t_order = Clock::now();
    const ScreenTiling tiling{rs.width, rs.height, rs.tile_size};
    in.items = sweep_order(topo, in.sv, in.cls, clipped, events, in.near, in.z_origin, tiling, std::move(given.items),
                           &given.words);
    std::vector<SweepEvent>().swap(events);
    std::vector<uint8_t>().swap(clipped);
    const auto t_bins = Clock::now();
    S.ms_order = ms_since(t_order);
    in.bins = bin_items(in.items, topo, in.sv, in.near, tiling, std::move(given.words));
    S.ms_binning = ms_since(t_bins);
    S.faces_offscreen = in.items.offscreen;
    S.faces_degenerate = in.items.degenerate;
    S.bin_entries = in.bins.items.size();
  }
};

ZSweepRenderer::ZSweepRenderer(const TetMesh& mesh, const Topology& topo, const RenderSettings& settings,
                               uint64_t sink_bytes, ViewBuffers* reuse)
    : impl_(std::make_unique<Impl>(mesh, topo, settings, sink_bytes, reuse)) {}
ZSweepRenderer::~ZSweepRenderer() = default;
const TileGrid& ZSweepRenderer::grid() const { return impl_->grid; }
const RenderStats& ZSweepRenderer::setup_stats() const { return impl_->setup; }

int ZSweepRenderer::threads() const { return std::max(1, impl_->rs.threads); }

void ZSweepRenderer::set_opaque_layer(const OpaqueLayer* layer) { impl_->in.under = layer; }

void ZSweepRenderer::render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles, RenderStats* stats) {
  Impl& I = *impl_;
  const auto t0 = Clock::now();
  std::vector<uint32_t> all;
  if (!tiles) {
    all = all_tiles(I.grid);
    tiles = &all;
  }
  uint64_t work = 0;
  for (uint32_t t : *tiles) work += I.in.bins.offset[t + 1] - I.in.bins.offset[t] + 1;
  Progress progress("render", work, I.rs.progress);
  auto& spaces = I.spaces;
  // Each thread's counters on their own cache lines (they change per fragment).
  struct alignas(128) PaddedStats : RenderStats {};
  tbb::enumerable_thread_specific<PaddedStats> tile_stats;
  run_tiles(I.grid, *tiles, threads(), sink, [&](uint32_t t, const TileRect& r) -> const float* {
    TileWorkspace& ws = spaces.local();
    sweep_tile(I.in, t, Viewport{int(r.x0), int(r.y0), int(r.x1), int(r.y1)}, I.plan.max_fragments, ws,
               tile_stats.local());
    progress.add(I.in.bins.offset[t + 1] - I.in.bins.offset[t] + 1);
    return ws.out.data();
  });
  progress.finish();
  if (!stats) return;
  for (const RenderStats& s : tile_stats) add_stats(*stats, s);
  stats->ms_total += ms_since(t0);
  stats->peak_rss_bytes = std::max(stats->peak_rss_bytes, peak_rss_bytes());
}

void ZSweepRenderer::render_tiles(TileSink& sink, const std::vector<uint32_t>* tiles) {
  render_tiles(sink, tiles, &impl_->totals);
}

std::vector<uint8_t> ZSweepRenderer::tile_totals() const { return pod_bytes(impl_->totals); }

void ZSweepRenderer::add_tile_totals(const std::vector<uint8_t>& other) {
  RenderStats o;
  if (!pod_from_bytes(other, &o)) throw std::runtime_error("ZSweep tile totals of the wrong size");
  RenderStats& T = impl_->totals;
  add_stats(T, o);
  T.ms_total += o.ms_total;
  T.peak_rss_bytes = std::max(T.peak_rss_bytes, o.peak_rss_bytes);
}

RenderStats ZSweepRenderer::stats() const {
  RenderStats s = impl_->setup;
  s.ms_total = s.ms_setup + impl_->totals.ms_total;
  add_stats(s, impl_->totals);
  s.peak_rss_bytes = std::max(s.peak_rss_bytes, impl_->totals.peak_rss_bytes);
  return s;
}

namespace {
// Fills a stats record with the setup part, then the tiles' part.
void begin_stats(const ZSweepRenderer& r, RenderStats* st) {
  *st = r.setup_stats();
  st->ms_total = st->ms_setup;
}
}  // namespace

void render_zsweep_tiles(const TetMesh& mesh, const Topology& topo, const RenderSettings& rs, TileSink& sink,
                         uint64_t sink_bytes, RenderStats* st) {
  RenderStats local;
  RenderStats& S = st ? *st : local;
  ZSweepRenderer r(mesh, topo, rs, sink_bytes);
  begin_stats(r, &S);
  r.render_tiles(sink, nullptr, &S);
}

Image render_zsweep(const TetMesh& mesh, const Topology& topo, const RenderSettings& rs, RenderStats* st) {
  if (rs.width == 0 || rs.height == 0) throw std::runtime_error("image size must be at least 1x1");
  const uint64_t image_bytes = uint64_t(rs.width) * rs.height * 16;
  const uint64_t budget = rs.budget();
  if (image_bytes >= budget)
    throw std::runtime_error("memory budget of " + bytes_str(budget) + " cannot hold a " + std::to_string(rs.width) +
                             "x" + std::to_string(rs.height) + " float image (" + bytes_str(image_bytes) + ")");
  ZSweepRenderer r(mesh, topo, rs, image_bytes);  // checks the budget before the image is allocated
  ImageSink sink(r.grid());
  RenderStats local;
  RenderStats& S = st ? *st : local;
  begin_stats(r, &S);
  r.render_tiles(sink, nullptr, &S);
  return std::move(sink.image);
}

}  // namespace zs
