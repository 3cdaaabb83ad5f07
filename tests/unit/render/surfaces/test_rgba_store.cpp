// render/surfaces/rgba_store.h: the interleaved RGBA store (a vector path for whole
// groups of 16 pixels, one pixel at a time for the rest) against its
// definition, at every batch length up to 64 and with background pixels
// scattered through the groups.
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "render/surfaces/rgba_store.h"

namespace zs {
namespace {

TEST(RgbaStore, EveryLengthAndBackgroundPattern) {
  constexpr uint32_t kNone = 0xffffffffu;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0.f, 1.f);
  const float bg[4] = {0.1f, -0.2f, 0.3f, 0.5f};
  int backgrounds = 0;
  for (int n = 0; n <= 64; ++n)
    for (int trial = 0; trial < 8; ++trial) {
      const size_t count = size_t(n);
      std::vector<float> r(count), g(count), b(count);
      std::vector<uint32_t> id(count);
      for (int i = 0; i < n; ++i) {
        r[i] = U(rng), g[i] = U(rng), b[i] = U(rng);
        id[i] = U(rng) < 0.3f ? kNone : uint32_t(i);
        backgrounds += id[i] == kNone;
      }
      std::vector<float> out(size_t(4 * n + 4), -7.f);  // one pixel past the end stays untouched
      store_rgba(n, r.data(), g.data(), b.data(), id.data(), kNone, bg, out.data());
      for (int i = 0; i < n; ++i) {
        const float want[4] = {r[i], g[i], b[i], 1.f};
        const float* w = id[i] == kNone ? bg : want;
        ASSERT_EQ(0, std::memcmp(out.data() + 4 * i, w, sizeof want)) << "n " << n << " pixel " << i;
      }
      for (int c = 0; c < 4; ++c) EXPECT_EQ(out[size_t(4 * n + c)], -7.f);
    }
  EXPECT_GT(backgrounds, 1000);
}

}  // namespace
}  // namespace zs
