#include "raster/triangle_bins.h"

#include <algorithm>
#include <cmath>

namespace zs {

namespace {

// The tile columns (or rows) [*a, *b] of the pixel centres in [lo, hi]; false
// when there are none inside [0, n).
bool tile_range(double lo, double hi, uint32_t n, uint32_t size, uint32_t* a, uint32_t* b) {
  if (!(hi >= 0) || !(lo <= double(n) - 1)) return false;  // NaN-safe
  const double l = std::max(0.0, std::ceil(lo)), h = std::min(double(n) - 1, std::floor(hi));
  if (l > h) return false;
  *a = uint32_t(l) / size;
  *b = uint32_t(h) / size;
  return true;
}

}  // namespace

void bin_triangles(const TileGrid& grid, const std::vector<ScreenVertex>& verts,
                   const std::vector<std::array<uint32_t, 3>>& corners, TriangleBins* out) {
  const uint32_t cols = grid.cols();
  out->offsets.assign(size_t(grid.count()) + 1, 0);
  // Two passes: count, then fill (no per-tile vectors).
  auto each = [&](auto&& f) {
    for (size_t t = 0; t < corners.size(); ++t) {
      const ScreenVertex &a = verts[corners[t][0]], &b = verts[corners[t][1]], &c = verts[corners[t][2]];
      uint32_t c0, c1, r0, r1;
      if (!tile_range(std::min({a.x, b.x, c.x}), std::max({a.x, b.x, c.x}), grid.width, grid.size, &c0, &c1) ||
          !tile_range(std::min({a.y, b.y, c.y}), std::max({a.y, b.y, c.y}), grid.height, grid.size, &r0, &r1))
        continue;
      for (uint32_t r = r0; r <= r1; ++r)
        for (uint32_t q = c0; q <= c1; ++q) f(r * cols + q, uint32_t(t));
    }
  };
  each([&](uint32_t tile, uint32_t) { ++out->offsets[tile + 1]; });
  for (size_t i = 1; i < out->offsets.size(); ++i) out->offsets[i] += out->offsets[i - 1];
  out->ids.resize(out->offsets.back());
  std::vector<uint64_t> fill(out->offsets.begin(), out->offsets.end() - 1);
  each([&](uint32_t tile, uint32_t t) { out->ids[fill[tile]++] = t; });
}

}  // namespace zs
