// The sweep's event heap (vertex_heap.h): pops in (depth, id) order whatever
// the input order, with many equal depths, after assign() and after push().
#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "render/volume/vertex_heap.h"

namespace zs {
namespace {

TEST(VertexHeap, PopsInDepthThenIdOrder) {
  std::mt19937 rng(3);
  for (int n : {0, 1, 2, 3, 7, 64, 1000, 4097}) {
    std::vector<VertexHeap::Entry> e;
    // Negative, zero (both signs) and positive depths, many of them equal.
    for (int i = 0; i < n; ++i) e.push_back({double(int(rng() % 50) - 25) * 0.25, uint32_t(rng() % 100000)});
    if (n > 3) e[1].z = -0.0, e[2].z = 0.0;
    std::vector<VertexHeap::Entry> want = e;
    std::sort(want.begin(), want.end(), [](auto& a, auto& b) { return a.z < b.z || (a.z == b.z && a.v < b.v); });
    VertexHeap h;
    h.assign(e);
    VertexHeap g;  // the same through push()
    for (const auto& x : e) g.push(x.z, x.v);
    for (int i = 0; i < n; ++i) {
      const VertexHeap::Entry a = h.pop(), b = g.pop();
      ASSERT_EQ(a.z, want[size_t(i)].z) << n << " " << i;  // -0 == +0
      ASSERT_EQ(a.v, want[size_t(i)].v) << n << " " << i;
      ASSERT_EQ(b.z, a.z);
      ASSERT_EQ(b.v, a.v);
    }
    EXPECT_TRUE(h.empty());
    EXPECT_TRUE(g.empty());
  }
}

}  // namespace
}  // namespace zs
