// The sweep's event order (sweep_events.h): (depth, id) whatever the input
// order, with many equal depths and both signed zeros, on any thread count.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "render/volume/sweep_events.h"

namespace zs {
namespace {

TEST(SweepEvents, SortedInDepthThenIdOrder) {
  std::mt19937 rng(3);
  for (int n : {0, 1, 2, 3, 7, 64, 1000, 4097, 300000}) {
    std::vector<SweepEvent> e;
    // Negative, zero (both signs) and positive depths, many of them equal.
    for (int i = 0; i < n; ++i) e.push_back({double(int(rng() % 50) - 25) * 0.25, uint32_t(rng() % 100000)});
    if (n > 3) e[1].z = -0.0, e[2].z = 0.0;
    std::vector<SweepEvent> want = e;
    std::sort(want.begin(), want.end(), [](auto& a, auto& b) { return a.z < b.z || (a.z == b.z && a.v < b.v); });
    for (int threads : {1, 2}) {
      std::vector<SweepKey> keys;
      tbb::task_arena(threads).execute([&] { keys = sorted_events(e); });
      ASSERT_EQ(keys.size(), size_t(n));
      for (int i = 0; i < n; ++i) {
        const SweepEvent a = sweep_event(keys[size_t(i)]);
        ASSERT_EQ(a.z, want[size_t(i)].z) << n << " " << i;  // -0 == +0
        ASSERT_EQ(a.v, want[size_t(i)].v) << n << " " << i;
      }
    }
  }
}

// Large lists go through depth buckets: spread, crowded into a few buckets,
// with a range too wide to bucket, and with a NaN (sorted last, as the key orders it).
TEST(SweepEvents, BucketedSortMatchesAPlainSort) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.5, 3.0);
  for (int pattern = 0; pattern < 4; ++pattern) {
    std::vector<SweepEvent> e;
    for (uint32_t i = 0; i < 200000; ++i) {
      double z = u(rng);
      if (pattern == 1) z = i % 100 == 0 ? 1e6 : std::round(z * 1e3) * 1e-9;  // one far depth, the rest in one bucket
      if (pattern == 2 && i == 7) z = -1e308, e.push_back({1e308, i + 1000000});
      if (pattern == 3 && i == 9) z = NAN;
      e.push_back({z, uint32_t(rng() % 400000)});
    }
    std::vector<SweepKey> want(e.size());
    for (size_t i = 0; i < e.size(); ++i) want[i] = sweep_key(e[i].z, e[i].v);
    std::sort(want.begin(), want.end());
    for (int threads : {1, 3}) {
      std::vector<SweepKey> keys;
      tbb::task_arena(threads).execute([&] { keys = sorted_events(e); });
      ASSERT_TRUE(keys == want) << "pattern " << pattern << ", " << threads << " threads";
    }
  }
}

TEST(SweepEvents, KeyRoundTripsDepthAndId) {
  for (double z : {-1e300, -2.5, -0.0, 0.0, 1e-310, 3.0, 1e300})
    for (uint32_t v : {0u, 7u, UINT32_MAX}) {
      const SweepEvent e = sweep_event(sweep_key(z, v));
      EXPECT_EQ(e.z, z);
      EXPECT_EQ(e.v, v);
    }
}

}  // namespace
}  // namespace zs
