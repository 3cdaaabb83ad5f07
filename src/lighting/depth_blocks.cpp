#include "lighting/depth_blocks.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace zs {

void DepthBlocks::reset(uint32_t map_size) {
  size = map_size;
  blocks = (map_size + (1u << kDepthBlockShift) - 1) >> kDepthBlockShift;
  min.assign(size_t(blocks) * blocks, INFINITY);
  max.assign(size_t(blocks) * blocks, INFINITY);  // empty blocks: every texel +inf
}

void fold_block_ranges(const float* z, size_t stride, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1,
                       DepthBlocks& out) {
  const uint32_t B = 1u << kDepthBlockShift, w = x1 - x0;
  // Per block row: each column's min and max down the block's rows (whole
  // rows at a time, so the loops vectorize), then each block's over its
  // columns. The comparisons are std::min/std::max's, in their order (a NaN,
  // never stored, would not lower the minimum).
  float lo_s[256], hi_s[256];
  std::vector<float> lo_v, hi_v;
  float* lo = lo_s;
  float* hi = hi_s;
  if (w > 256) {
    lo_v.resize(w), hi_v.resize(w);
    lo = lo_v.data(), hi = hi_v.data();
  }
  for (uint32_t by = y0 >> kDepthBlockShift; by <= (y1 - 1) >> kDepthBlockShift; ++by) {
    for (uint32_t x = 0; x < w; ++x) lo[x] = INFINITY, hi[x] = -INFINITY;
    for (uint32_t y = std::max(y0, by * B); y < std::min(y1, (by + 1) * B); ++y) {
      const float* row = z + size_t(y - y0) * stride;
      for (uint32_t x = 0; x < w; ++x) {
        const float v = row[x];
        lo[x] = v < lo[x] ? v : lo[x];
        hi[x] = hi[x] < v ? v : hi[x];
      }
    }
    for (uint32_t bx = x0 >> kDepthBlockShift; bx <= (x1 - 1) >> kDepthBlockShift; ++bx) {
      float m = INFINITY, M = -INFINITY;
      for (uint32_t x = std::max(x0, bx * B); x < std::min(x1, (bx + 1) * B); ++x) {
        m = std::min(m, lo[x - x0]);
        M = std::max(M, hi[x - x0]);
      }
      out.min[size_t(by) * out.blocks + bx] = m;
      out.max[size_t(by) * out.blocks + bx] = M;
    }
  }
}

void dilate_block_ranges(DepthBlocks& b) {
  const int n = int(b.blocks);
  std::vector<float> lo(b.min.size()), hi(b.max.size());
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      float m = INFINITY, M = -INFINITY;
      for (int j = std::max(0, y - 1); j <= std::min(n - 1, y + 1); ++j)
        for (int i = std::max(0, x - 1); i <= std::min(n - 1, x + 1); ++i) {
          m = std::min(m, b.min[size_t(j) * n + i]);
          M = std::max(M, b.max[size_t(j) * n + i]);
        }
      lo[size_t(y) * n + x] = m;
      hi[size_t(y) * n + x] = M;
    }
  b.min.swap(lo);
  b.max.swap(hi);
}

}  // namespace zs
