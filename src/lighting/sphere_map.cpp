#include "lighting/sphere_map.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "raster/tile_loop.h"
#include "lighting/depth_blocks.h"
#include "lighting/tiled_depths.h"
#include "lighting/transmittance_lists.h"

namespace zs {

namespace {
constexpr int kBlocks = int(kMapTile / 8);  // 8×8-texel blocks per tile side
constexpr uint32_t kOrderBuckets = 64;       // depth slices of a tile's disc order
constexpr uint32_t kSkipTest = 16;           // discs of a bucket worth testing it whole
}  // namespace

// A sphere's disc in a map: centre in texels, depth, radius in texels.
struct SphereDisc {
  double x, y, z, r;
  uint32_t id;  // sphere
};

// What a map's set-up allocates, kept from map to map by a thread (large
// fresh allocations cost a page fault per 4 KiB page, a good part of a map).
struct SphereMapScratch {
  std::vector<SphereDisc> discs, bins;
  std::vector<uint32_t> count, fill;
  std::vector<double> floor;
};

namespace {

using Disc = SphereDisc;

// The set's box, grown by the radii: the map covers every sphere whole.
Bounds sphere_box(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii) {
  Bounds box;
  for (size_t i = 0; i < centres.size(); ++i) {
    const glm::dvec3 lo = centres[i] - glm::dvec3(radii[i]), hi = centres[i] + glm::dvec3(radii[i]);
    if (!(radii[i] > 0) || !std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z)) continue;  // not drawn
    box.lo = box.empty ? lo : glm::min(box.lo, lo);
    box.hi = box.empty ? hi : glm::max(box.hi, hi);
    box.empty = false;
  }
  return box;
}

// The map's frame: orthographic along the light, fitted to the box's
// corners (spheres digest §2.4.5, building the map for ω).
Camera map_frame(const Light& light, const Bounds& box, uint32_t D) {
  LightFit fit = start_fit(light);
  for (int c = 0; c < 8 && !box.empty; ++c)
    fit.add({c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z});
  double z_near = 0;
  return shadow_map_frame(light, fit, box, D, &z_near);
}

// One map's discs, binned to its tiles in a thread's scratch: what every
// tile of the map reads.
struct MapDiscs {
  uint32_t D;
  TileGrid grid;
  double texel;  // world size of a texel
  bool disc_mode;
  const std::vector<float>* alpha;  // null: every sphere opaque
  SphereMapScratch& sc;

  bool opaque(uint32_t i) const { return !alpha || (*alpha)[i] >= 1.f; }
  // The disc's nearest depth (a centre disc: its only one).
  double nearest(const Disc& d) const { return disc_mode ? d.z + 0.0 : d.z - d.r * texel; }

  // Calls fn(tile) for each tile the disc's texel square touches.
  template <class Fn>
  void tiles_of(const Disc& d, Fn&& fn) const {
    const int x0 = std::max(0, int(std::ceil(d.x - d.r))), x1 = std::min(int(D) - 1, int(std::floor(d.x + d.r)));
    const int y0 = std::max(0, int(std::ceil(d.y - d.r))), y1 = std::min(int(D) - 1, int(std::floor(d.y + d.r)));
    if (x0 > x1 || y0 > y1) return;
    for (int ty = y0 >> kMapTileShift; ty <= (y1 >> kMapTileShift); ++ty)
      for (int tx = x0 >> kMapTileShift; tx <= (x1 >> kMapTileShift); ++tx) fn(uint32_t(ty) * grid.cols() + tx);
  }

  // A tile whose every texel centre lies inside an opaque centre disc (the
  // four corner centres do: distance to the centre is largest at a corner,
  // and its rounding is monotone too) starts at that disc's depth instead of
  // binning it: large spheres (C2's maximal balls cover ~25 tiles of a
  // 1024² map each) would otherwise be copied into, and read by, every tile
  // under them. Drawing the disc would give each texel the same minimum.
  bool covers(const Disc& d, uint32_t t) const {
    if (!disc_mode || !opaque(d.id)) return false;
    const double xa = double((t % grid.cols()) * kMapTile), ya = double((t / grid.cols()) * kMapTile);
    const double xb = std::min(xa + kMapTile, double(D)) - 1, yb = std::min(ya + kMapTile, double(D)) - 1;
    const double r2 = d.r * d.r, dxa = xa - d.x, dxb = xb - d.x, dya = ya - d.y, dyb = yb - d.y;
    return dxa * dxa + dya * dya <= r2 && dxb * dxb + dya * dya <= r2 && dxa * dxa + dyb * dyb <= r2 &&
           dxb * dxb + dyb * dyb <= r2;
  }

  // Each sphere's disc, the tiles it covers (their floors), and per other
  // tile it touches, the count of discs binned there.
  void project(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii, const View& view) {
    std::vector<Disc>& discs = sc.discs;
    discs.resize(centres.size());
    std::vector<uint32_t>& count = sc.count;
    count.assign(grid.count() + 1, 0);
    std::vector<double>& floor = sc.floor;
    floor.assign(grid.count(), INFINITY);
    for (size_t i = 0; i < centres.size(); ++i) {
      const ViewPoint v = view.project(centres[i]);
      Disc& d = discs[i];
      d = {v.x, v.y, v.z, radii[i] / texel, uint32_t(i)};
      if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && d.r > 0)) d.r = -1;  // not drawn
      if (alpha && !((*alpha)[i] > 0.f)) d.r = -1;  // alpha 0 (or NaN) lets all light through
      tiles_of(d, [&](uint32_t t) {
        if (covers(d, t))
          floor[t] = std::min(floor[t], d.z + 0.0);
        else
          ++count[t + 1];
      });
    }
  }

  // The bins hold copies of the discs, so that a tile reads its own in one
  // run of memory instead of gathering them from the whole set.
  void fill_bins() {
    std::vector<uint32_t>& count = sc.count;
    for (size_t t = 0; t < grid.count(); ++t) count[t + 1] += count[t];
    sc.bins.resize(count.back());
    std::vector<uint32_t>& fill = sc.fill;
    fill.assign(count.begin(), count.end() - 1);
    for (const Disc& d : sc.discs)
      tiles_of(d, [&](uint32_t t) {
        if (!covers(d, t)) sc.bins[fill[t]++] = d;
      });
  }

  // The tiles with a disc or a floor, added to `centre`: the others hold no caster.
  std::vector<uint32_t> busy_tiles(TiledDepths& centre) const {
    std::vector<uint32_t> busy;
    for (uint32_t t = 0; t < grid.count(); ++t)
      if (sc.count[t + 1] != sc.count[t] || sc.floor[t] < INFINITY) {
        busy.push_back(t);
        centre.add_tile(t % grid.cols(), t / grid.cols());
      }
    return busy;
  }
};

// A thread's buffers for a map's tiles.
struct TileWork {
  std::vector<double> db;
  std::vector<float> out;
  std::vector<TranslucentTexel> frags;
  std::vector<uint32_t> order;  // the tile's opaque discs (bin entries), nearer first
  std::vector<uint8_t> slot;    // their depth slices
  double bmax[kBlocks * kBlocks];  // per 8×8 block: its farthest depth
  bool dirty[kBlocks * kBlocks];   // ... written since it was computed
  uint64_t written = 0;
};

// One tile of a map, drawn by one thread: its depths start at its floor,
// take the minimum of its opaque discs, nearest first, and then list the
// translucent discs in front of them.
struct DiscTile {
  DiscTile(const MapDiscs& discs, TileWork& work, uint32_t tile, const TileRect& rect)
      : md(discs), w(work), t(tile), r(rect), W(rect.width()), H(rect.height()) {
    w.db.assign(size_t(W) * H, md.sc.floor[t]);
    std::fill(w.bmax, w.bmax + kBlocks * kBlocks, md.sc.floor[t]);
    std::fill(w.dirty, w.dirty + kBlocks * kBlocks, false);
  }

  // The opaque discs, nearer first (by kOrderBuckets depth slices of the
  // tile's range, a counting sort: cheaper than sorting, and the order only
  // decides how many later discs are skipped whole). The minimum depends
  // neither on the order nor on a skipped disc.
  void draw_opaque() {
    order_opaque();
    const std::vector<Disc>& bins = md.sc.bins;
    const bool disc_mode = md.disc_mode;
    for (uint32_t b = 0; b < kOrderBuckets; ++b) {
      const uint32_t k0 = b == 0 ? 0 : first[b - 1], k1 = first[b];
      // (Checked for buckets large enough to pay for the tile's 64 block
      // maxima; the discs of a small one are tested one by one anyway.)
      if (k0 == k1 || (k1 - k0 >= kSkipTest && bucket_near[b] >= tile_far())) continue;
      for (uint32_t q = k0; q < k1; ++q) {
        const Disc& d = bins[w.order[q]];
        far_stale |= rows(d, md.nearest(d), [&](int y, int xa, int xb, double dy2) {
          double* o = w.db.data() + size_t(y) * W;
          if (disc_mode) {
            const double z = d.z + 0.0;
            for (int x = xa; x <= xb; ++x) o[x] = std::min(o[x], z);
          } else {
            for (int x = xa; x <= xb; ++x) o[x] = std::min(o[x], depth_at(d, x, dy2));
          }
        });
      }
    }
  }

  // Translucent discs in front of the tile's opaque depths: a point behind
  // those is blocked whatever lies between.
  void list_translucent(TransmittanceLists& lists) {
    const std::vector<uint32_t>& count = md.sc.count;
    const bool disc_mode = md.disc_mode;
    w.frags.clear();
    for (uint32_t k = count[t]; k < count[t + 1]; ++k) {
      const Disc& d = md.sc.bins[k];
      const uint32_t id = d.id;
      if (md.opaque(id)) continue;
      const double pass = 1.0 - double((*md.alpha)[id]);
      rows(d, md.nearest(d), [&](int y, int xa, int xb, double dy2) {
        const double* o = w.db.data() + size_t(y) * W;
        for (int x = xa; x <= xb; ++x) {
          const double z = disc_mode ? d.z + 0.0 : depth_at(d, x, dy2);
          if (z < o[x]) w.frags.push_back({uint32_t(y) * kMapTile + uint32_t(x), id, z, pass});
        }
      });
    }
    lists.set_tile(r.x0 >> kMapTileShift, r.y0 >> kMapTileShift, w.frags);
  }

  // The depths rounded up to floats, with their blocks' ranges.
  const float* finish(DepthBlocks& blocks) {
    w.out.resize(w.db.size());
    round_depths_up(w.db.data(), w.db.size(), w.out.data());
    fold_block_ranges(w.out.data(), W, r.x0, r.y0, r.x1, r.y1, blocks);  // whole blocks per tile
    return w.out.data();
  }

  // The farthest depth of block (bx, by), recomputed when written since.
  double block_far(int bx, int by) {
    const int b = by * kBlocks + bx;
    if (w.dirty[b]) {
      double m = -INFINITY;
      for (uint32_t y = by * 8; y < std::min<uint32_t>(H, by * 8 + 8); ++y)
        for (uint32_t x = bx * 8; x < std::min<uint32_t>(W, bx * 8 + 8); ++x) m = std::max(m, w.db[size_t(y) * W + x]);
      w.bmax[b] = m;
      w.dirty[b] = false;
    }
    return w.bmax[b];
  }

  // Calls fn(y, xa, xb, dy²) for the runs of texel centres xa..xb of each
  // row y of the tile (tile coordinates) inside the disc: exactly those
  // with (x−cx)² + (y−cy)² <= r² (the square root gives the run, the exact
  // test its ends), and only over the 8×8 blocks where the disc is nearer
  // than the block's farthest depth (`znear`: the disc's nearest depth;
  // elsewhere it could change nothing: the thesis's early-z, spheres digest
  // §2.4.5, per block). False when no block under its box is open.
  static_assert(kBlocks * kBlocks <= 64, "a tile's open blocks fit one 64-bit mask");
  template <class Fn>
  bool rows(const Disc& d, double znear, Fn&& fn) {
    const int x0 = std::max(int(r.x0), int(std::ceil(d.x - d.r)));
    const int x1 = std::min(int(r.x1) - 1, int(std::floor(d.x + d.r)));
    const int y0 = std::max(int(r.y0), int(std::ceil(d.y - d.r)));
    const int y1 = std::min(int(r.y1) - 1, int(std::floor(d.y + d.r)));
    if (x0 > x1 || y0 > y1) return false;
    const int bx0 = (x0 - int(r.x0)) >> 3, bx1 = (x1 - int(r.x0)) >> 3;
    const int by0 = (y0 - int(r.y0)) >> 3, by1 = (y1 - int(r.y0)) >> 3;
    uint64_t open = 0;
    for (int by = by0; by <= by1; ++by)
      for (int bx = bx0; bx <= bx1; ++bx)
        if (znear < block_far(bx, by)) open |= uint64_t(1) << (by * kBlocks + bx);
    if (!open) return false;
    const bool all_open = std::popcount(open) == (bx1 - bx0 + 1) * (by1 - by0 + 1);  // most small discs
    const double r2 = d.r * d.r;
    auto inside = [&](int x, double dy2) {
      const double dx = x - d.x;
      return dx * dx + dy2 <= r2;
    };
    for (int y = y0; y <= y1; ++y) {
      const uint64_t row_open = open >> (((y - int(r.y0)) >> 3) * kBlocks);
      if ((row_open & ((uint64_t(1) << kBlocks) - 1)) == 0) continue;
      const double dy = y - d.y, dy2 = dy * dy;
      const double h = std::sqrt(std::max(0.0, r2 - dy2));
      int xa = std::max(x0, int(std::ceil(d.x - h))), xb = std::min(x1, int(std::floor(d.x + h)));
      while (xa <= xb && !inside(xa, dy2)) ++xa;
      while (xa > x0 && inside(xa - 1, dy2)) --xa;
      while (xb >= xa && !inside(xb, dy2)) --xb;
      while (xb < x1 && xb >= xa && inside(xb + 1, dy2)) ++xb;
      if (xa > xb) continue;
      const int ta = xa - int(r.x0), tb = xb - int(r.x0), yt = y - int(r.y0);
      if (all_open) {
        fn(yt, ta, tb, dy2);
        w.written += uint64_t(tb - ta + 1);
        continue;
      }
      // The run cut to its open blocks.
      for (int b = ta >> 3; b <= (tb >> 3);) {
        if (!((row_open >> b) & 1)) {
          ++b;
          continue;
        }
        int e = b;
        while (e + 1 <= (tb >> 3) && ((row_open >> (e + 1)) & 1)) ++e;
        const int sa = std::max(ta, b * 8), sb = std::min(tb, e * 8 + 7);
        fn(yt, sa, sb, dy2);
        w.written += uint64_t(sb - sa + 1);
        b = e + 1;
      }
    }
    for (int q = 0; q < kBlocks * kBlocks; ++q)
      if ((open >> q) & 1) w.dirty[q] = true;
    return true;
  }

  // The disc's depth at texel x of a row (impostor: the front surface,
  // r·√(1 − ρ²/r²) nearer than the centre).
  double depth_at(const Disc& d, int xt, double dy2) const {
    const double r2 = d.r * d.r, dx = xt + int(r.x0) - d.x;
    return d.z - d.r * md.texel * std::sqrt(std::max(0.0, 1 - (dx * dx + dy2) / r2)) + 0.0;
  }

  // The counting sort of the opaque discs into w.order: bucket b's discs
  // end at first[b], the nearest of them at bucket_near[b].
  void order_opaque() {
    const std::vector<uint32_t>& count = md.sc.count;
    const std::vector<Disc>& bins = md.sc.bins;
    double zlo = INFINITY, zhi = -INFINITY;
    for (uint32_t k = count[t]; k < count[t + 1]; ++k) {
      const double z = md.nearest(bins[k]);
      zlo = std::min(zlo, z), zhi = std::max(zhi, z);
    }
    const double zs = zhi > zlo ? (kOrderBuckets - 0.5) / (zhi - zlo) : 0.0;
    std::fill(bucket_near, bucket_near + kOrderBuckets, INFINITY);
    w.slot.resize(count[t + 1] - count[t]);
    for (uint32_t k = count[t]; k < count[t + 1]; ++k) {
      const uint32_t b = md.opaque(bins[k].id) ? uint32_t((md.nearest(bins[k]) - zlo) * zs) : kOrderBuckets;
      w.slot[k - count[t]] = uint8_t(b);
      ++first[b];
      if (b < kOrderBuckets) bucket_near[b] = std::min(bucket_near[b], md.nearest(bins[k]));
    }
    for (uint32_t b = 0, sum = 0; b <= kOrderBuckets; ++b) {
      const uint32_t c = first[b];
      first[b] = sum;
      sum += c;
    }
    w.order.resize(first[kOrderBuckets]);  // the opaque ones
    for (uint32_t k = count[t]; k < count[t + 1]; ++k) {
      const uint8_t b = w.slot[k - count[t]];
      if (b < kOrderBuckets) w.order[first[b]++] = k;
    }
  }

  // The tile's farthest depth: a bucket whose discs are all at least that
  // far changes nothing and is skipped without reading its discs (a tile
  // covered early by large near discs skips most of its list).
  double tile_far() {
    if (far_stale) {
      far_cached = -INFINITY;
      for (int by = 0; by < kBlocks; ++by)
        for (int bx = 0; bx < kBlocks; ++bx) far_cached = std::max(far_cached, block_far(bx, by));
      far_stale = false;
    }
    return far_cached;
  }

  const MapDiscs& md;
  TileWork& w;
  const uint32_t t;
  const TileRect& r;
  const uint32_t W, H;
  uint32_t first[kOrderBuckets + 1] = {};
  double bucket_near[kOrderBuckets];  // the nearest depth of each bucket's discs
  double far_cached = INFINITY;
  bool far_stale = true;  // a disc was drawn since far_cached was computed
};

}  // namespace

ShadowMap build_sphere_map(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii,
                           const glm::dvec3& omega, uint32_t D, SphereDepth mode, const ShadowSettings& s,
                           int threads, SphereMapStats* stats, const std::vector<float>* alpha,
                           TransmittanceLists* translucent, SphereMapScratch* scratch) {
  SphereMapScratch own;
  const auto t0 = std::chrono::steady_clock::now();
  Light light;
  light.type = LightType::Directional;
  light.direction = -omega;
  const Camera frame = map_frame(light, sphere_box(centres, radii), D);
  MapDiscs m{D, TileGrid{D, D, kMapTile, 1}, frame.height / D, mode == SphereDepth::CentreDisc, alpha,
             scratch ? *scratch : own};
  m.project(centres, radii, View(frame, D, D));
  m.fill_bins();
  // Alpha occluders: 0 < α < 1 goes to the lists, α >= 1 (and every sphere
  // without alpha) to the depths.
  if (translucent) translucent->reset(D);
  TiledDepths centre;
  centre.reset(D, 1);
  DepthBlocks blocks;
  blocks.reset(D);
  const std::vector<uint32_t> busy = m.busy_tiles(centre);
  tbb::enumerable_thread_specific<TileWork> work;
  TiledDepthsSink sink(centre);
  run_tiles(m.grid, busy, threads, sink, [&](uint32_t t, const TileRect& r) -> const float* {
    DiscTile tile(m, work.local(), t, r);
    tile.draw_opaque();
    if (translucent) tile.list_translucent(*translucent);
    return tile.finish(blocks);
  });
  if (stats) {
    stats->texels_written = 0;
    for (const TileWork& w : work) stats->texels_written += w.written;
    stats->ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  if (translucent) translucent->count_fragments();
  return ShadowMap::from_tiles(light, frame, std::move(centre), s, std::move(blocks));
}

SphereAoMaps build_sphere_ao_maps(const std::vector<glm::dvec3>& centres, const std::vector<double>& radii,
                                  const std::vector<glm::dvec3>& dirs, uint32_t size, SphereDepth mode,
                                  const ShadowSettings& s, int threads, const std::vector<float>* alpha) {
  const auto t0 = std::chrono::steady_clock::now();
  SphereAoMaps out;
  out.dirs = dirs;
  out.maps.resize(dirs.size());
  if (alpha) out.translucent.resize(dirs.size());
  tbb::enumerable_thread_specific<SphereMapScratch> scratch;
  auto one = [&](size_t k, int t) {
    out.maps[k] = build_sphere_map(centres, radii, dirs[k], size, mode, s, t, nullptr, alpha,
                                   alpha ? &out.translucent[k] : nullptr, &scratch.local());
  };
  threads = std::max(1, threads);
  if (int(dirs.size()) >= threads && threads > 1) {
    tbb::task_arena arena(threads);
    arena.execute([&] { tbb::parallel_for(size_t(0), dirs.size(), [&](size_t k) { one(k, 1); }); });
  } else {
    for (size_t k = 0; k < dirs.size(); ++k) one(k, threads);
  }
  for (const ShadowMap& m : out.maps) out.bytes += m.bytes();
  for (const TransmittanceLists& l : out.translucent) out.bytes += l.bytes(), out.translucent_fragments += l.fragments();
  out.ms_build = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

// N·ω, in glm::dot's order: the weight accumulate_ao and ao_weights add.
inline double ao_weight(double nx, double ny, double nz, const glm::dvec3& d) { return nx * d.x + ny * d.y + nz * d.z; }

void accumulate_ao(const SphereAoMaps& ao, size_t n, const double* px, const double* py, const double* pz,
                   const double* nx, const double* ny, const double* nz, double* num, double* den) {
  // By chunks of points; per direction, the points it faces are gathered and
  // looked up in one batch (ShadowMap::lit_counts), then added in direction
  // order, so every point's sums are the per-point loop's, bit for bit.
  constexpr size_t kChunk = 64;
  double qx[kChunk], qy[kChunk], qz[kChunk], mx[kChunk], my[kChunk], mz[kChunk], wk[kChunk];
  uint32_t idx[kChunk], lit[kChunk];
  for (size_t i0 = 0; i0 < n; i0 += kChunk) {
    const size_t m = std::min(kChunk, n - i0);
    for (size_t k = 0; k < ao.dirs.size(); ++k) {
      const glm::dvec3 d = ao.dirs[k];
      size_t c = 0;
      for (size_t i = 0; i < m; ++i) {
        const size_t j = i0 + i;
        const double w = ao_weight(nx[j], ny[j], nz[j], d);
        if (!(w > 0)) continue;
        qx[c] = px[j], qy[c] = py[j], qz[c] = pz[j], mx[c] = nx[j], my[c] = ny[j], mz[c] = nz[j];
        wk[c] = w, idx[c] = uint32_t(j);
        ++c;
      }
      if (c == 0) continue;
      const ShadowMap& map = ao.maps[k];
      map.lit_counts(c, qx, qy, qz, mx, my, mz, lit);
      const TransmittanceLists* tl = ao.translucent.empty() ? nullptr : &ao.translucent[k];
      for (size_t q = 0; q < c; ++q) {
        double v = double(lit[q]) / double(map.levels());
        if (tl && v > 0 && tl->fragments()) {
          uint32_t x, y;
          double lim;
          map.locate({qx[q], qy[q], qz[q]}, {mx[q], my[q], mz[q]}, &x, &y, &lim);
          v *= double(tl->transmittance(x, y, lim));
        }
        den[idx[q]] += wk[q];
        num[idx[q]] += wk[q] * v;
      }
    }
  }
}

void ao_weights(const std::vector<glm::dvec3>& dirs, size_t n, const double* nx, const double* ny, const double* nz,
                double* den) {
  for (const glm::dvec3& d : dirs)
    for (size_t i = 0; i < n; ++i) {
      const double w = ao_weight(nx[i], ny[i], nz[i], d);
      if (w > 0) den[i] += w;
    }
}

double ambient_occlusion(const SphereAoMaps& ao, const glm::dvec3& p, const glm::dvec3& n) {
  double num = 0, den = 0;
  accumulate_ao(ao, 1, &p.x, &p.y, &p.z, &n.x, &n.y, &n.z, &num, &den);
  return den > 0 ? num / den : 1.0;
}

}  // namespace zs
