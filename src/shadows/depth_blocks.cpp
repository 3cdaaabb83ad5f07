#include "shadows/depth_blocks.h"

#include <cmath>

namespace zs {

void DepthBlocks::reset(uint32_t map_size) {
  size = map_size;
  blocks = (map_size + (1u << kDepthBlockShift) - 1) >> kDepthBlockShift;
  min.assign(size_t(blocks) * blocks, INFINITY);
  max.assign(size_t(blocks) * blocks, INFINITY);  // empty blocks: every texel +inf
}

void fold_block_ranges(const float* z, size_t stride, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1,
                       DepthBlocks& out) {
  const uint32_t B = 1u << kDepthBlockShift;
  for (uint32_t by = y0 >> kDepthBlockShift; by <= (y1 - 1) >> kDepthBlockShift; ++by)
    for (uint32_t bx = x0 >> kDepthBlockShift; bx <= (x1 - 1) >> kDepthBlockShift; ++bx) {
      float m = INFINITY, M = -INFINITY;
      for (uint32_t y = std::max(y0, by * B); y < std::min(y1, (by + 1) * B); ++y)
        for (uint32_t x = std::max(x0, bx * B); x < std::min(x1, (bx + 1) * B); ++x) {
          const float v = z[size_t(y - y0) * stride + (x - x0)];
          m = std::min(m, v);  // NaN never stored; would not lower m
          M = std::max(M, v);
        }
      out.min[size_t(by) * out.blocks + bx] = m;
      out.max[size_t(by) * out.blocks + bx] = M;
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
