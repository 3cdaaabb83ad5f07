#include "render/volume/sweep_order.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "base/util/chunk_offsets.h"

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
constexpr uint64_t kBuckets = 1024;        // rank buckets of the order's first pass
constexpr size_t kChunkFaces = 1 << 16;   // faces per chunk of the order's passes

struct Dropped {
  uint64_t degenerate = 0, offscreen = 0;
  void add(Cover c) { ++(c == Cover::Degenerate ? degenerate : offscreen); }
};

}  // namespace

SweepItems sweep_order(const Topology& topo, const std::vector<ScreenVertex>& sv, const std::vector<FaceClass>& cls,
                       const std::vector<uint8_t>& done, const std::vector<SweepEvent>& events,
                       const std::vector<NearTriangle>& near, double z_origin, const ScreenTiling& tiling,
                       UninitVector<SweepItem> storage, UninitVector<uint32_t>* words) {
  SweepItems it;
  it.items = std::move(storage);
  it.items.clear();
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
  // smallest rank among them. Faces of one vertex follow in id order. Faces
  // that cannot produce a fragment are dropped. The order is a two-level
  // counting sort: faces are scattered into buckets of consecutive ranks
  // (few enough that every bucket's write position stays in cache), then each
  // bucket is sorted by rank in cache. Chunks of faces are laid out in face
  // order inside a bucket and the sort is stable, so ties stay in id order
  // whatever the thread count.
  const uint32_t nf = uint32_t(topo.num_faces());
  uint32_t shift = 0;
  while ((uint64_t(n_events) >> shift) > kBuckets) ++shift;
  const size_t nb = (size_t(n_events) >> shift) + 1;
  const size_t chunks = std::clamp<size_t>(nf / kChunkFaces, 1, 16 * size_t(tbb::this_task_arena::max_concurrency()));
  auto chunk_begin = [&](size_t c) { return uint32_t(uint64_t(nf) * c / chunks); };
  // Per face: its rank (kDropped: left out) and its single tile, found here
  // once rather than again in the scattered fill below; two words a face, in
  // the caller's array when it gives one (it becomes the bins' next).
  UninitVector<uint32_t> own;
  UninitVector<uint32_t>& keys = words ? *words : own;
  if (keys.size() < 2 * size_t(nf)) keys.resize(2 * size_t(nf));
  uint32_t* key = keys.data();
  std::vector<uint64_t> at(chunks * nb, 0);  // chunk c's entries in bucket b: at[c * nb + b]
  tbb::combinable<Dropped> dropped;
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    Dropped& d = dropped.local();
    uint64_t* count = at.data() + c * nb;
    for (uint32_t f = chunk_begin(c); f < chunk_begin(c + 1); ++f) {
      key[2 * size_t(f)] = kDropped;
      if ((!done.empty() && done[f]) || cls[f] == FaceClass::Culled) continue;
      const auto fv = topo.face(f);
      const uint32_t rk = std::min({rank[fv[0]], rank[fv[1]], rank[fv[2]]});
      if (rk == kDropped) continue;  // no vertex in front of the near plane: clipped
      const ScreenVertex v[3] = {sv[fv[0]], sv[fv[1]], sv[fv[2]]};
      uint32_t tile = 0;
      const Cover cv = cover(v, tiling, &tile);
      if (cv != Cover::Yes) {
        d.add(cv);
        continue;
      }
      key[2 * size_t(f)] = rk;
      key[2 * size_t(f) + 1] = tile;
      ++count[rk >> shift];
    }
  });
  it.degenerate = near_dropped.degenerate;
  it.offscreen = near_dropped.offscreen;
  dropped.combine_each([&](const Dropped& d) {
    it.degenerate += d.degenerate;
    it.offscreen += d.offscreen;
  });
  // Bucket-major, then chunk: where chunk c's entries of bucket b start.
  const std::vector<uint64_t> bucket_start = chunk_offsets(at, chunks, nb, it.size());
  it.items.resize(bucket_start[nb]);
  // The scatter carries each face's rank in place of its plane depth.
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint64_t* pos = at.data() + c * nb;
    for (uint32_t f = chunk_begin(c); f < chunk_begin(c + 1); ++f) {
      const uint32_t rk = key[2 * size_t(f)];
      if (rk == kDropped) continue;
      it.items[pos[rk >> shift]++] = {f, std::bit_cast<float>(rk), key[2 * size_t(f) + 1]};
    }
  });
  UninitVector<uint32_t>().swap(own);
  std::vector<uint64_t>().swap(at);
  // Each bucket: a stable counting sort by rank through a per-thread buffer,
  // with the plane's depth written in place of the rank.
  struct Scratch {
    std::vector<uint32_t> count;
    std::vector<SweepItem> out;
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::parallel_for(size_t(0), nb, [&](size_t b) {
    SweepItem* lo = it.items.data() + bucket_start[b];
    const size_t n = bucket_start[b + 1] - bucket_start[b];
    if (n == 0) return;
    Scratch& s = scratch.local();
    const uint32_t r0 = uint32_t(b << shift);
    s.count.assign((size_t(1) << shift) + 1, 0);
    for (size_t k = 0; k < n; ++k) ++s.count[std::bit_cast<uint32_t>(lo[k].z_sweep) - r0 + 1];
    for (size_t r = 1; r < s.count.size(); ++r) s.count[r] += s.count[r - 1];
    s.out.resize(n);
    for (size_t k = 0; k < n; ++k) {
      const uint32_t rk = std::bit_cast<uint32_t>(lo[k].z_sweep);
      s.out[s.count[rk - r0]++] = {lo[k].id, z_at[rk], lo[k].tile};
    }
    std::copy(s.out.begin(), s.out.end(), lo);
  });
  return it;
}

}  // namespace zs
