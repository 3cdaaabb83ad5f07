// PixelLists / PixelRecord: sorted insertion into the inline slots and the
// pooled overflow list, the pool's budget and counters, and consuming the
// fragments front to back the way the compositor does (drop_front / clear).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "render/volume/pixel_lists.h"

namespace zs {
namespace {

struct Frag {
  float z, s;
  uint32_t kind;
};
// The order PixelLists promises: depth, then exit < interior < entry.
bool frag_less(const Frag& a, const Frag& b) { return a.z < b.z || (a.z == b.z && a.kind < b.kind); }

PixelRecord fresh() {
  PixelRecord px;
  px.reset();
  return px;
}

// Consumes the pixel's fragments one at a time from the front (as the
// unbatched compositor does) and returns them in order.
std::vector<Frag> drain_one_by_one(PixelRecord& px, PixelLists& lists) {
  std::vector<Frag> out;
  while (px.n > 0) {
    out.push_back({px.z[0], px.s[0], px.kind(0)});
    lists.drop_front(px, 1);
  }
  return out;
}

// Consumes them in chunks of everything inline (as the batched compositor
// does when every inline fragment is final).
std::vector<Frag> drain_inline_chunks(PixelRecord& px, PixelLists& lists) {
  std::vector<Frag> out;
  while (px.n > 0) {
    for (int i = 0; i < px.n; ++i) out.push_back({px.z[i], px.s[i], px.kind(i)});
    lists.drop_front(px, px.n);
  }
  return out;
}

TEST(PixelLists, ResetRecordIsEmpty) {
  PixelRecord px = fresh();
  EXPECT_EQ(px.n, 0);
  EXPECT_EQ(px.pending(), 0u);
  EXPECT_TRUE(std::isinf(px.z[0]) && px.z[0] > 0);  // "before z" is one compare
  EXPECT_EQ(px.head, kNil);
  EXPECT_EQ(px.tail, kNil);
  EXPECT_EQ(px.inside, 0);
  EXPECT_EQ(px.done, 0);
}

TEST(PixelLists, InlineSortedInsertionKeepsScalarsAndKinds) {
  PixelLists lists;
  lists.reset(16);
  PixelRecord px = fresh();
  // Out of order, with a depth tie resolved by kind (exit before entry).
  EXPECT_EQ(lists.insert_counted(px, 3.0f, 30.f, kEntry), 1u);
  EXPECT_EQ(lists.insert_counted(px, 1.0f, 10.f, kInterior), 2u);
  EXPECT_EQ(lists.insert_counted(px, 3.0f, 31.f, kExit), 3u);
  EXPECT_EQ(lists.insert_counted(px, 2.0f, 20.f, kEntry), 4u);
  ASSERT_EQ(px.n, 4);
  EXPECT_EQ(px.pending(), 4u);
  EXPECT_EQ(px.head, kNil);  // nothing overflowed
  EXPECT_EQ(lists.overflow_fragments(), 0u);
  const float ez[4] = {1, 2, 3, 3}, es[4] = {10, 20, 31, 30};
  const uint32_t ek[4] = {kInterior, kEntry, kExit, kEntry};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(px.z[i], ez[i]) << i;
    EXPECT_EQ(px.s[i], es[i]) << i;
    EXPECT_EQ(px.kind(i), ek[i]) << i;
  }
  // Same depth and kind: the later insert goes behind (stable).
  PixelRecord q = fresh();
  lists.insert(q, 5.f, 1.f, kExit);
  lists.insert(q, 5.f, 2.f, kExit);
  EXPECT_EQ(q.s[0], 1.f);
  EXPECT_EQ(q.s[1], 2.f);
}

TEST(PixelLists, OverflowKeepsSortedOrderForEveryPermutation) {
  // 23 fragments: far more than the 4 inline slots, with depth ties of
  // different kinds. Any insertion order gives the same sorted sequence.
  std::vector<Frag> frags;
  for (int i = 0; i < 23; ++i) frags.push_back({float(i / 3), float(100 + i), uint32_t(i % 3)});
  std::vector<Frag> sorted = frags;
  std::sort(sorted.begin(), sorted.end(), frag_less);
  std::mt19937 rng(1234);
  PixelLists lists;
  for (int trial = 0; trial < 300; ++trial) {
    lists.reset(1000);
    std::shuffle(frags.begin(), frags.end(), rng);
    PixelRecord px = fresh();
    for (size_t i = 0; i < frags.size(); ++i) {
      const uint32_t pending = lists.insert_counted(px, frags[i].z, frags[i].s, frags[i].kind);
      ASSERT_EQ(pending, i + 1);
      ASSERT_EQ(px.pending(), i + 1);
      ASSERT_EQ(px.n, std::min<size_t>(i + 1, kInline));
      ASSERT_EQ(lists.overflow_fragments(), i + 1 > kInline ? i + 1 - kInline : 0);
    }
    lists.add_live(frags.size());
    EXPECT_EQ(px.ovf, frags.size() - kInline);
    EXPECT_EQ(lists.live_fragments(), frags.size());
    const std::vector<Frag> got = trial % 2 ? drain_one_by_one(px, lists) : drain_inline_chunks(px, lists);
    ASSERT_EQ(got.size(), sorted.size());
    for (size_t i = 0; i < got.size(); ++i) {
      ASSERT_EQ(got[i].z, sorted[i].z) << "trial " << trial << " i " << i;
      ASSERT_EQ(got[i].s, sorted[i].s) << "trial " << trial << " i " << i;
      ASSERT_EQ(got[i].kind, sorted[i].kind) << "trial " << trial << " i " << i;
    }
    // Empty again: record, pool and counters.
    EXPECT_EQ(px.pending(), 0u);
    EXPECT_EQ(px.head, kNil);
    EXPECT_EQ(px.tail, kNil);
    EXPECT_TRUE(std::isinf(px.z[0]));
    EXPECT_EQ(lists.overflow_fragments(), 0u);
    EXPECT_EQ(lists.live_fragments(), 0u);
    EXPECT_EQ(lists.peak_fragments(), frags.size());
    EXPECT_EQ(lists.peak_overflow_fragments(), frags.size() - kInline);
  }
}

TEST(PixelLists, InterleavedInsertAndConsumeStaysSorted) {
  // The sweep's pattern: fragments arrive roughly in depth order, the front
  // ones are consumed while deeper ones keep arriving (into the overflow).
  // Checked against a sorted multiset model.
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> dz(0.f, 4.f);
  std::uniform_int_distribution<int> kind(0, 2), op(0, 9);
  PixelLists lists;
  lists.reset(1 << 20);
  PixelRecord px = fresh();
  std::vector<Frag> model;
  float front = 0;
  size_t inserted = 0, consumed = 0;
  for (int step = 0; step < 20000; ++step) {
    if (op(rng) < 6 || model.empty()) {
      const Frag f{front + dz(rng), float(step), uint32_t(kind(rng))};
      ASSERT_TRUE(lists.insert(px, f.z, f.s, f.kind));
      lists.add_live(1);
      model.insert(std::upper_bound(model.begin(), model.end(), f, frag_less), f);
      ++inserted;
    } else {
      const int k = std::uniform_int_distribution<int>(1, px.n)(rng);
      for (int i = 0; i < k; ++i) {
        ASSERT_EQ(px.z[i], model[size_t(i)].z);
        ASSERT_EQ(px.s[i], model[size_t(i)].s);
        ASSERT_EQ(px.kind(i), model[size_t(i)].kind);
      }
      front = px.z[k - 1];
      lists.drop_front(px, k);
      model.erase(model.begin(), model.begin() + k);
      consumed += size_t(k);
    }
    ASSERT_EQ(px.pending(), model.size());
    ASSERT_EQ(lists.live_fragments(), model.size());
    ASSERT_EQ(lists.overflow_fragments(), model.size() > kInline ? model.size() - kInline : 0);
    // Inline slots are full whenever anything is in the overflow.
    ASSERT_TRUE(px.head == kNil || px.n == kInline);
  }
  EXPECT_GT(consumed, 1000u);
  EXPECT_EQ(inserted - consumed, model.size());
}

TEST(PixelLists, BudgetRejectsOnceOverflowPoolIsFull) {
  PixelLists lists;
  lists.reset(3);
  EXPECT_EQ(lists.max_overflow(), 3u);
  PixelRecord a = fresh(), b = fresh();
  // 4 inline + 3 overflow fit in pixel a.
  for (int i = 0; i < 7; ++i) ASSERT_TRUE(lists.insert(a, float(10 + 2 * i), float(i), kInterior)) << i;
  lists.add_live(7);
  EXPECT_EQ(lists.overflow_fragments(), 3u);
  // A deeper fragment (append) and a shallower one (an inline fragment would
  // be pushed to the overflow) both need a slot: rejected, pixel untouched.
  EXPECT_FALSE(lists.insert(a, 100.f, 0.f, kExit));
  EXPECT_EQ(lists.insert_counted(a, 1.f, 0.f, kEntry), 0u);
  EXPECT_EQ(lists.insert_counted(a, 15.f, 0.f, kEntry), 0u);
  EXPECT_EQ(a.pending(), 7u);
  EXPECT_EQ(a.z[0], 10.f);
  // Another pixel shares the pool: its inline slots are free, its overflow is not.
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(lists.insert(b, float(i), 0.f, kEntry));
  lists.add_live(4);
  EXPECT_FALSE(lists.insert(b, 50.f, 0.f, kEntry));
  EXPECT_FALSE(lists.insert(b, -1.f, 0.f, kEntry));
  EXPECT_EQ(b.pending(), 4u);
  EXPECT_EQ(b.z[0], 0.f);
  EXPECT_EQ(b.z[3], 3.f);
  EXPECT_EQ(lists.live_fragments(), 11u);
  EXPECT_EQ(lists.peak_fragments(), 11u);
  EXPECT_EQ(lists.peak_overflow_fragments(), 3u);
  // Consuming two of a's fragments frees two slots (moved up inline); b can overflow again.
  lists.drop_front(a, 2);
  EXPECT_EQ(a.pending(), 5u);
  EXPECT_EQ(a.n, kInline);
  EXPECT_EQ(lists.overflow_fragments(), 1u);
  EXPECT_EQ(lists.live_fragments(), 9u);
  ASSERT_TRUE(lists.insert(b, 50.f, 0.f, kEntry));
  ASSERT_TRUE(lists.insert(b, -1.f, 7.f, kEntry));  // pushes b's z = 3 to the overflow
  EXPECT_FALSE(lists.insert(b, 60.f, 0.f, kEntry));
  lists.add_live(2);
  EXPECT_EQ(b.z[0], -1.f);
  EXPECT_EQ(b.s[0], 7.f);
  EXPECT_EQ(lists.overflow_fragments(), 3u);
  EXPECT_EQ(lists.peak_fragments(), 11u);  // 9 + 2
  // clear() gives everything back.
  lists.clear(a);
  lists.clear(b);
  EXPECT_EQ(a.pending(), 0u);
  EXPECT_EQ(b.pending(), 0u);
  EXPECT_EQ(lists.overflow_fragments(), 0u);
  EXPECT_EQ(lists.live_fragments(), 0u);
  EXPECT_EQ(lists.peak_overflow_fragments(), 3u);
}

TEST(PixelLists, ZeroBudgetAllowsInlineOnly) {
  PixelLists lists;
  lists.reset(0);
  PixelRecord px = fresh();
  for (int i = 0; i < kInline; ++i) EXPECT_TRUE(lists.insert(px, float(i), 0.f, kEntry));
  EXPECT_FALSE(lists.insert(px, 9.f, 0.f, kEntry));
  EXPECT_FALSE(lists.insert(px, -9.f, 0.f, kEntry));
  EXPECT_EQ(px.pending(), uint32_t(kInline));
  EXPECT_EQ(lists.overflow_fragments(), 0u);
}

TEST(PixelLists, PoolGrowsPastItsFirstBlockUpToTheBound) {
  // The pool grows on demand (1024 slots first, then doubling) and stops at
  // the bound exactly, whatever the block size.
  PixelLists lists;
  const size_t bound = 2500;
  lists.reset(bound);
  std::vector<PixelRecord> px(700);
  for (auto& p : px) p.reset();
  size_t ok = 0;
  // 700 pixels x 8 fragments: 2800 overflow wanted, 2500 available.
  for (int round = 0; round < 8; ++round)
    for (size_t i = 0; i < px.size(); ++i) ok += lists.insert(px[i], float(8 - round), float(i), kInterior);
  EXPECT_EQ(ok, 700u * kInline + bound);
  EXPECT_EQ(lists.overflow_fragments(), bound);
  lists.add_live(ok);
  // Each pixel's list is intact and sorted.
  size_t drained = 0;
  for (size_t i = 0; i < px.size(); ++i) {
    const auto got = drain_one_by_one(px[i], lists);
    for (size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].s, float(i));
      if (k) ASSERT_LT(got[k - 1].z, got[k].z);
    }
    drained += got.size();
  }
  EXPECT_EQ(drained, ok);
  EXPECT_EQ(lists.live_fragments(), 0u);
  EXPECT_EQ(lists.overflow_fragments(), 0u);
}

TEST(PixelLists, ReuseAfterResetStartsFromZeroWithANewBound) {
  PixelLists lists;
  lists.reset(100);
  PixelRecord px = fresh();
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(lists.insert(px, float(i), 0.f, kEntry));
  lists.add_live(50);
  EXPECT_EQ(lists.peak_fragments(), 50u);
  EXPECT_EQ(lists.peak_overflow_fragments(), 46u);
  // The next tile: records are reset, counters too; the storage is kept but
  // the new (smaller) bound applies.
  lists.reset(5);
  px.reset();
  EXPECT_EQ(lists.max_overflow(), 5u);
  EXPECT_EQ(lists.live_fragments(), 0u);
  EXPECT_EQ(lists.peak_fragments(), 0u);
  EXPECT_EQ(lists.overflow_fragments(), 0u);
  EXPECT_EQ(lists.peak_overflow_fragments(), 0u);
  int ok = 0;
  for (int i = 0; i < 20; ++i) ok += lists.insert(px, float(20 - i), float(i), kExit);
  EXPECT_EQ(ok, kInline + 5);
  lists.add_live(size_t(ok));
  const auto got = drain_inline_chunks(px, lists);
  ASSERT_EQ(got.size(), size_t(ok));
  for (size_t k = 1; k < got.size(); ++k) EXPECT_LT(got[k - 1].z, got[k].z);
  // Inserted 20..1 descending; the first 9 accepted are 20..12, sorted 12..20.
  EXPECT_EQ(got.front().z, 12.f);
  EXPECT_EQ(got.back().z, 20.f);
  // A bound beyond the 32-bit index space is clamped below kNil.
  lists.reset(size_t(1) << 40);
  EXPECT_EQ(lists.max_overflow(), size_t(kNil) - 1);
}

TEST(PixelLists, DropFrontMovesOverflowUp) {
  PixelLists lists;
  lists.reset(64);
  PixelRecord px = fresh();
  for (int i = 9; i >= 0; --i) ASSERT_TRUE(lists.insert(px, float(i), float(10 * i), uint32_t(i % 3)));
  lists.add_live(10);
  ASSERT_EQ(px.n, kInline);
  ASSERT_EQ(px.ovf, 6);
  lists.drop_front(px, 3);  // 0,1,2 gone; 3 stays; 4,5,6 move up
  EXPECT_EQ(px.n, kInline);
  EXPECT_EQ(px.ovf, 3);
  EXPECT_EQ(px.pending(), 7u);
  for (int i = 0; i < kInline; ++i) {
    EXPECT_EQ(px.z[i], float(3 + i));
    EXPECT_EQ(px.s[i], float(10 * (3 + i)));
    EXPECT_EQ(px.kind(i), uint32_t((3 + i) % 3));
  }
  EXPECT_EQ(lists.live_fragments(), 7u);
  EXPECT_EQ(lists.overflow_fragments(), 3u);
  lists.drop_front(px, 4);  // 7,8,9 move up, the overflow is empty
  EXPECT_EQ(px.n, 3);
  EXPECT_EQ(px.ovf, 0);
  EXPECT_EQ(px.head, kNil);
  EXPECT_EQ(px.tail, kNil);
  EXPECT_EQ(px.z[0], 7.f);
  EXPECT_EQ(px.z[2], 9.f);
  // Now not full: a deeper fragment goes inline again, a shallower one sorts in.
  EXPECT_EQ(lists.insert_counted(px, 8.5f, 85.f, kEntry), 4u);
  EXPECT_EQ(px.z[2], 8.5f);
  EXPECT_EQ(px.z[3], 9.f);
  EXPECT_EQ(px.kind(2), uint32_t(kEntry));
  EXPECT_EQ(px.kind(3), 0u);
  EXPECT_EQ(lists.overflow_fragments(), 0u);
  lists.drop_front(px, 4);
  EXPECT_TRUE(std::isinf(px.z[0]));
}

TEST(PixelLists, SaturatedOverflowCountDrainsCompletely) {
  // More than 65535 overflow fragments in one pixel: the overflow count
  // saturates (pending() stays an underestimate) but nothing is lost.
  PixelLists lists;
  lists.reset(1 << 20);
  PixelRecord px = fresh();
  const uint32_t N = 70000;
  for (uint32_t i = 0; i < N; ++i) ASSERT_TRUE(lists.insert(px, float(i), float(i), kInterior));
  lists.add_live(N);
  EXPECT_EQ(px.ovf, UINT16_MAX);
  EXPECT_EQ(px.pending(), uint32_t(kInline) + UINT16_MAX);
  EXPECT_EQ(lists.overflow_fragments(), size_t(N - kInline));
  uint32_t k = 0;
  while (px.n > 0) {
    for (int i = 0; i < px.n; ++i, ++k) ASSERT_EQ(px.z[i], float(k));
    lists.drop_front(px, px.n);
  }
  EXPECT_EQ(k, N);
  EXPECT_EQ(px.pending(), 0u);
  EXPECT_EQ(lists.live_fragments(), 0u);
  EXPECT_EQ(lists.overflow_fragments(), 0u);
}

}  // namespace
}  // namespace zs
