#include "render/volume/tile_bins.h"

namespace zs {

TileBins bin_items(const SweepItems& items, const ScreenTiling& t) {
  TileBins b;
  b.cols = (t.width + t.tile - 1) / t.tile;
  b.rows = (t.height + t.tile - 1) / t.tile;
  b.offset.assign(size_t(b.cols) * b.rows + 1, 0);
  for (const TileBox& x : items.box)
    for (uint32_t r = x.r0; r <= x.r1; ++r)
      for (uint32_t c = x.c0; c <= x.c1; ++c) ++b.offset[size_t(r) * b.cols + c + 1];
  for (size_t k = 1; k < b.offset.size(); ++k) b.offset[k] += b.offset[k - 1];
  b.items.resize(b.offset.back());
  std::vector<uint64_t> fill(b.offset.begin(), b.offset.end() - 1);
  for (size_t k = 0; k < items.size(); ++k) {
    const TileBox& x = items.box[k];
    for (uint32_t r = x.r0; r <= x.r1; ++r)
      for (uint32_t c = x.c0; c <= x.c1; ++c) b.items[fill[size_t(r) * b.cols + c]++] = uint32_t(k);
  }
  return b;
}

}  // namespace zs
