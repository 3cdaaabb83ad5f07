// Per 8×8-texel block of a shadow map, the smallest and largest depth a
// lookup inside it can read: exact early outs for the test. When a point's
// limit d − bias is at most the minimum over the blocks its kernel touches,
// every one of the k·n comparisons passes (fully lit); when it is above the
// maximum, every one fails (in shadow). Either way the map is not read. Most
// lookups end there (open ground, the inside of shadows), and the block
// arrays (1/64 of the map each) stay in cache where the map would not.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace zs {

constexpr uint32_t kDepthBlockShift = 3;  // 8×8 texels

struct DepthBlocks {
  uint32_t size = 0;        // texels per side of the map
  uint32_t blocks = 0;      // blocks per side
  std::vector<float> min, max;  // blocks² each, +inf where empty

  void reset(uint32_t map_size);
  // The minimum and maximum over the blocks holding texels [x0, x1] × [y0, y1]
  // (in range).
  void range(int x0, int y0, int x1, int y1, float* lo, float* hi) const {
    const int b0 = x0 >> kDepthBlockShift, b1 = x1 >> kDepthBlockShift;
    float m = INFINITY, M = -INFINITY;
    for (int by = y0 >> kDepthBlockShift; by <= (y1 >> kDepthBlockShift); ++by)
      for (int bx = b0; bx <= b1; ++bx) {
        m = std::min(m, min[size_t(by) * blocks + size_t(bx)]);
        M = std::max(M, max[size_t(by) * blocks + size_t(bx)]);
      }
    *lo = m;
    *hi = M;
  }
};

// Folds texels [x0, x1) × [y0, y1) of a map (row pointer `z`, `stride` floats
// per row, texel (x0, y0) first) into the blocks, whose texels must all be
// folded by one call (a tile of whole blocks, or the whole map).
void fold_block_ranges(const float* z, size_t stride, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1,
                       DepthBlocks& out);

// Each block takes the minimum and maximum of its 3×3 blocks: the bounds for
// an n-SM whose extra depths come from a texel's neighbours (one texel away).
void dilate_block_ranges(DepthBlocks& b);

}  // namespace zs
