#include "render/volume/sweep_events.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

namespace zs {

std::vector<SweepKey> sorted_events(const std::vector<SweepEvent>& events) {
  std::vector<SweepKey> keys(events.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, events.size(), 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) keys[i] = sweep_key(events[i].z, events[i].v);
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  return keys;
}

}  // namespace zs
