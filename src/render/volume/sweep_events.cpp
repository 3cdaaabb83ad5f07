#include "render/volume/sweep_events.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>

#include "base/util/chunk_offsets.h"
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

namespace zs {

namespace {

constexpr size_t kBuckets = 4096;     // depth buckets: a few thousand events each at 10 M
constexpr size_t kChunk = 1 << 16;    // events per chunk of the bucketing passes

}  // namespace

std::vector<SweepKey> sorted_events(const std::vector<SweepEvent>& events) {
  const size_t n = events.size();
  std::vector<SweepKey> keys(n);
  double lo = INFINITY, hi = -INFINITY;
  bool nan = false;
  for (const SweepEvent& e : events) {
    lo = std::min(lo, e.z), hi = std::max(hi, e.z);
    nan = nan || std::isnan(e.z);
  }
  const double scale = double(kBuckets) / (hi - lo);
  // One sort of the whole list when it is small, or when the depths span no
  // finite range or hold a NaN (nothing to bucket by).
  if (n < 2 * kChunk || nan || !std::isfinite(scale) || !(scale > 0)) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kChunk), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) keys[i] = sweep_key(events[i].z, events[i].v);
    });
    tbb::parallel_sort(keys.begin(), keys.end());
    return keys;
  }
  // Buckets of equal depth range, in depth order (the map from depth to
  // bucket never decreases, so equal depths share one): a counting pass per
  // chunk, the keys scattered to their buckets, then each bucket sorted by
  // the full key in cache. The result is the one sorted order whatever the
  // threads; a crowded bucket only costs time.
  auto bucket = [&](double z) { return std::min(kBuckets - 1, size_t((z - lo) * scale)); };
  const size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<uint64_t> at(chunks * kBuckets, 0);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint64_t* count = at.data() + c * kBuckets;
    for (size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i) ++count[bucket(events[i].z)];
  });
  const std::vector<uint64_t> start = chunk_offsets(at, chunks, kBuckets);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint64_t* pos = at.data() + c * kBuckets;
    for (size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i)
      keys[pos[bucket(events[i].z)]++] = sweep_key(events[i].z, events[i].v);
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, kBuckets, 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t b = r.begin(); b < r.end(); ++b) std::sort(keys.begin() + start[b], keys.begin() + start[b + 1]);
  });
  return keys;
}

}  // namespace zs
