// DepthBuffer: order independence (ties by id), k-layer sorting, reset.
#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "raster/depth_buffer.h"

namespace zs {
namespace {

struct Sample {
  size_t p;
  double z;
  uint32_t id;
};

// Random samples with many exact depth ties (depths from a small set).
std::vector<Sample> random_samples(std::mt19937& rng, size_t pixels, size_t n) {
  std::uniform_int_distribution<size_t> P(0, pixels - 1);
  std::uniform_int_distribution<int> Z(0, 6);
  std::uniform_int_distribution<uint32_t> I(0, 40);
  std::vector<Sample> s(n);
  for (Sample& x : s) x = {P(rng), 0.25 * Z(rng), I(rng)};
  return s;
}

void expect_same(const DepthBuffer& a, const DepthBuffer& b) {
  ASSERT_EQ(a.layers(), b.layers());
  const size_t n = size_t(a.width()) * a.height();
  for (uint32_t l = 0; l < a.layers(); ++l)
    for (size_t p = 0; p < n; ++p) {
      ASSERT_EQ(a.id(p, l), b.id(p, l)) << p << " layer " << l;
      const double da = a.depth(p, l), db = b.depth(p, l);
      ASSERT_EQ(std::signbit(da), std::signbit(db));
      ASSERT_TRUE(da == db || (std::isinf(da) && std::isinf(db)));
    }
}

TEST(DepthBuffer, TestWriteIsOrderIndependent) {
  std::mt19937 rng(5);
  std::vector<Sample> s = random_samples(rng, 12 * 9, 2000);
  s.push_back({3, -0.0, 7});  // ±0 must not depend on arrival order
  s.push_back({3, 0.0, 7});
  DepthBuffer ref;
  ref.reset(12, 9);
  for (const Sample& x : s) ref.test_write(x.p, x.z, x.id);
  // Expected front sample: the (z, id) minimum per pixel.
  for (size_t p = 0; p < 12 * 9; ++p) {
    double z = INFINITY;
    uint32_t id = kNoId;
    for (const Sample& x : s)
      if (x.p == p && std::tie(x.z, x.id) < std::tie(z, id)) z = x.z, id = x.id;
    EXPECT_EQ(ref.depth(p), z);
    EXPECT_EQ(ref.id(p), id);
  }
  EXPECT_FALSE(std::signbit(ref.depth(3)));
  for (int perm = 0; perm < 10; ++perm) {
    std::shuffle(s.begin(), s.end(), rng);
    DepthBuffer b;
    b.reset(12, 9);
    for (const Sample& x : s) b.test_write(x.p, x.z, x.id);
    expect_same(ref, b);
  }
}

TEST(DepthBuffer, TestWriteReturnAndTies) {
  DepthBuffer b;
  b.reset(2, 1);
  EXPECT_TRUE(b.passes(0, 5.0, 3));
  EXPECT_TRUE(b.test_write(0, 5.0, 3));
  EXPECT_FALSE(b.passes(0, 5.0, 3));     // not strictly in front of itself
  EXPECT_TRUE(b.test_write(0, 5.0, 3));  // ...but it is the front sample
  EXPECT_FALSE(b.passes(0, 5.0, 4));
  EXPECT_FALSE(b.test_write(0, 5.0, 4));  // equal depth, larger id loses
  EXPECT_TRUE(b.passes(0, 5.0, 2));
  EXPECT_TRUE(b.test_write(0, 5.0, 2));   // equal depth, smaller id wins
  EXPECT_EQ(b.id(0), 2u);
  EXPECT_FALSE(b.test_write(0, 6.0, 0));
  EXPECT_TRUE(b.test_write(0, 4.0, 9));
  EXPECT_EQ(b.depth(0), 4.0);
  EXPECT_EQ(b.id(0), 9u);
  EXPECT_FALSE(b.test_write(0, NAN, 0));
  EXPECT_EQ(b.depth(1), INFINITY);
  EXPECT_EQ(b.id(1), kNoId);
  EXPECT_EQ(b.depths()[0], 4.0);
}

TEST(DepthBuffer, KLayersHoldTheKNearestSorted) {
  std::mt19937 rng(11);
  const uint32_t W = 7, H = 5, K = 4;
  std::vector<Sample> s = random_samples(rng, W * H, 1500);
  DepthBuffer ref;
  ref.reset(W, H, K);
  for (const Sample& x : s) ref.insert(x.p, x.z, x.id);
  for (size_t p = 0; p < W * H; ++p) {
    std::vector<std::pair<double, uint32_t>> all;
    for (const Sample& x : s)
      if (x.p == p) all.push_back({x.z, x.id});
    std::sort(all.begin(), all.end());
    for (uint32_t l = 0; l < K; ++l) {
      if (l < all.size()) {
        EXPECT_EQ(ref.depth(p, l), all[l].first) << p << " " << l;
        EXPECT_EQ(ref.id(p, l), all[l].second) << p << " " << l;
      } else {
        EXPECT_EQ(ref.depth(p, l), INFINITY);
        EXPECT_EQ(ref.id(p, l), kNoId);
      }
    }
    EXPECT_EQ(ref.depths()[p], ref.depth(p, 0));
  }
  for (int perm = 0; perm < 10; ++perm) {
    std::shuffle(s.begin(), s.end(), rng);
    DepthBuffer b;
    b.reset(W, H, K);
    for (const Sample& x : s) b.insert(x.p, x.z, x.id);
    expect_same(ref, b);
  }
  // k = 1 insert agrees with test_write.
  DepthBuffer one, tw;
  one.reset(W, H, 1);
  tw.reset(W, H, 1);
  for (const Sample& x : s) one.insert(x.p, x.z, x.id), tw.test_write(x.p, x.z, x.id);
  expect_same(one, tw);
}

TEST(DepthBuffer, InsertReturnValue) {
  DepthBuffer b;
  b.reset(1, 1, 2);
  EXPECT_TRUE(b.insert(0, 3.0, 1));
  EXPECT_TRUE(b.insert(0, 2.0, 1));
  EXPECT_FALSE(b.insert(0, 3.0, 1));  // equals the last kept sample
  EXPECT_FALSE(b.insert(0, 3.0, 2));  // behind the last
  EXPECT_TRUE(b.insert(0, 3.0, 0));   // ties: smaller id in front of the last
  EXPECT_EQ(b.depth(0, 0), 2.0);
  EXPECT_EQ(b.id(0, 1), 0u);
  EXPECT_TRUE(b.insert(0, 1.0, 5));
  EXPECT_EQ(b.depth(0, 0), 1.0);
  EXPECT_EQ(b.depth(0, 1), 2.0);
  EXPECT_FALSE(b.insert(0, NAN, 0));
}

TEST(DepthBuffer, ResetClearsAndResizes) {
  DepthBuffer b;
  b.reset(4, 3, 2);
  for (size_t p = 0; p < 12; ++p) b.insert(p, double(p), uint32_t(p));
  b.reset(3, 2, 3);
  EXPECT_EQ(b.width(), 3u);
  EXPECT_EQ(b.height(), 2u);
  EXPECT_EQ(b.layers(), 3u);
  for (size_t p = 0; p < 6; ++p)
    for (uint32_t l = 0; l < 3; ++l) {
      EXPECT_EQ(b.depth(p, l), INFINITY);
      EXPECT_EQ(b.id(p, l), kNoId);
    }
  b.reset(4, 3);
  EXPECT_EQ(b.layers(), 1u);
  EXPECT_EQ(b.depths()[11], INFINITY);
}

}  // namespace
}  // namespace zs
