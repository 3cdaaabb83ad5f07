#include "render/volume/sweep_order.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

namespace zs {

bool pixel_range(const ScreenVertex v[3], uint32_t w, uint32_t h, int* i0, int* i1, int* j0, int* j1) {
  const double min_x = std::min({v[0].x, v[1].x, v[2].x}), max_x = std::max({v[0].x, v[1].x, v[2].x});
  const double min_y = std::min({v[0].y, v[1].y, v[2].y}), max_y = std::max({v[0].y, v[1].y, v[2].y});
  // Clamp in double first so huge coordinates never overflow the int
  // conversion; a NaN box compares false and is dropped.
  if (!(max_x >= 0 && min_x <= double(w) - 1 && max_y >= 0 && min_y <= double(h) - 1)) return false;
  *i0 = int(std::ceil(std::max(min_x, 0.0)));
  *i1 = int(std::floor(std::min(max_x, double(w) - 1)));
  *j0 = int(std::ceil(std::max(min_y, 0.0)));
  *j1 = int(std::floor(std::min(max_y, double(h) - 1)));
  return *i0 <= *i1 && *j0 <= *j1;
}

TileBox item_tile_box(const ScreenVertex v[3], const ScreenTiling& t) {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  pixel_range(v, t.width, t.height, &i0, &i1, &j0, &j1);
  return {uint32_t(i0) / t.tile, uint32_t(i1) / t.tile, uint32_t(j0) / t.tile, uint32_t(j1) / t.tile};
}

uint32_t single_tile(const TileBox& x, const ScreenTiling& t) {
  const uint32_t cols = (t.width + t.tile - 1) / t.tile;
  return x.c0 == x.c1 && x.r0 == x.r1 ? x.r0 * cols + x.c0 : kManyTiles;
}

namespace {

enum class Cover { Yes, Degenerate, Offscreen };

// Whether a triangle can produce fragments, and then its one tile (or
// kManyTiles): one pixel-range computation for both.
Cover cover(const ScreenVertex v[3], const ScreenTiling& t, uint32_t* tile) {
  const double det = screen_det(v);
  if (det == 0 || !std::isfinite(det)) return Cover::Degenerate;
  int i0, i1, j0, j1;
  if (!pixel_range(v, t.width, t.height, &i0, &i1, &j0, &j1)) return Cover::Offscreen;
  *tile = single_tile({uint32_t(i0) / t.tile, uint32_t(i1) / t.tile, uint32_t(j0) / t.tile, uint32_t(j1) / t.tile}, t);
  return Cover::Yes;
}

constexpr uint32_t kDropped = UINT32_MAX;
constexpr size_t kGrain = 1 << 14;

struct Dropped {
  uint64_t degenerate = 0, offscreen = 0;
  void add(Cover c) { ++(c == Cover::Degenerate ? degenerate : offscreen); }
};

}  // namespace

SweepItems sweep_order(const Topology& topo, const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                       const std::vector<uint8_t>& done, const std::vector<SweepEvent>& events,
                       const std::vector<NearTriangle>& near, double z_origin, const ScreenTiling& tiling) {
  SweepItems it;
  Dropped near_dropped;
  for (size_t k = 0; k < near.size(); ++k) {
    uint32_t tile = 0;
    const Cover c = cover(near[k].v, tiling, &tile);
    if (c != Cover::Yes) {
      near_dropped.add(c);
      continue;
    }
    it.items.push_back({kNearItem | uint32_t(k), -INFINITY, tile});
  }
  // The sweep: each event vertex's rank in sweep order, and the plane's depth there.
  const uint32_t n_events = uint32_t(events.size());
  std::vector<uint32_t> rank(sv.size(), kDropped);
  std::vector<float> z_at(n_events);
  {
    const std::vector<SweepKey> keys = sorted_events(events);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n_events, kGrain), [&](const tbb::blocked_range<uint32_t>& r) {
      for (uint32_t i = r.begin(); i < r.end(); ++i) {
        const SweepEvent ev = sweep_event(keys[i]);
        rank[ev.v] = i;
        z_at[i] = float(ev.z - z_origin);
      }
    });
  }
  // A face is projected when the first of its vertices is swept: at the
  // smallest rank among them. Faces of one vertex follow in id order. A
  // counting sort by that rank (filled in any order, then each rank's short
  // run sorted by id), dropping faces that cannot produce a fragment.
  const uint32_t nf = uint32_t(topo.num_faces());
  // Per face: its rank (kDropped: left out) and its single tile, found here
  // once rather than again in the scattered fill below.
  struct FaceKey {
    uint32_t rank = kDropped, tile = 0;
  };
  std::vector<FaceKey> key(nf);
  std::vector<uint32_t> start(size_t(n_events) + 1, 0);
  tbb::combinable<Dropped> dropped;
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, nf, kGrain), [&](const tbb::blocked_range<uint32_t>& r) {
    Dropped& d = dropped.local();
    for (uint32_t f = r.begin(); f < r.end(); ++f) {
      if ((!done.empty() && done[f]) || cls[f] == FaceClass::Culled) continue;
      const auto fv = topo.face(f);
      const uint32_t rk = std::min({rank[fv[0]], rank[fv[1]], rank[fv[2]]});
      if (rk == kDropped) continue;  // no vertex in front of the near plane: clipped
      const ScreenVertex v[3] = {sv[fv[0]], sv[fv[1]], sv[fv[2]]};
      uint32_t tile = 0;
      const Cover c = cover(v, tiling, &tile);
      if (c != Cover::Yes) {
        d.add(c);
        continue;
      }
      key[f] = {rk, tile};
      std::atomic_ref<uint32_t>(start[rk + 1]).fetch_add(1, std::memory_order_relaxed);
    }
  });
  it.degenerate = near_dropped.degenerate;
  it.offscreen = near_dropped.offscreen;
  dropped.combine_each([&](const Dropped& d) {
    it.degenerate += d.degenerate;
    it.offscreen += d.offscreen;
  });
  for (size_t r = 0; r < n_events; ++r) start[r + 1] += start[r];
  const size_t base = it.size(), total = base + start[n_events];
  it.items.resize(total);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, nf, kGrain), [&](const tbb::blocked_range<uint32_t>& r) {
      for (uint32_t f = r.begin(); f < r.end(); ++f) {
        const FaceKey fk = key[f];
        if (fk.rank == kDropped) continue;
        const size_t k = base + std::atomic_ref<uint32_t>(fill[fk.rank]).fetch_add(1, std::memory_order_relaxed);
        it.items[k] = {f, z_at[fk.rank], fk.tile};
      }
    });
  }
  std::vector<FaceKey>().swap(key);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n_events, kGrain / 4), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t rk = r.begin(); rk < r.end(); ++rk) {
      SweepItem* lo = it.items.data() + base + start[rk];
      SweepItem* hi = it.items.data() + base + start[rk + 1];
      if (hi - lo > 1) std::sort(lo, hi, [](const SweepItem& a, const SweepItem& b) { return a.id < b.id; });
    }
  });
  return it;
}

}  // namespace zs
