#include "volume/tile_bins.h"

#include <algorithm>
#include <cmath>

namespace zs {

void item_triangle(const SweepItems& items, size_t k, const Topology& topo, const std::vector<ScreenVertex>& sv,
                   const std::vector<NearTriangle>& near, ScreenVertex out[3]) {
  const uint32_t id = items.id[k];
  if (id & kNearItem) {
    const NearTriangle& nt = near[id & ~kNearItem];
    for (int c = 0; c < 3; ++c) out[c] = nt.v[c];
    return;
  }
  const auto& fv = topo.faces[id];
  for (int c = 0; c < 3; ++c) out[c] = sv[fv[c]];
}

bool pixel_range(const ScreenVertex v[3], uint32_t w, uint32_t h, int* i0, int* i1, int* j0, int* j1) {
  const double min_x = std::min({v[0].x, v[1].x, v[2].x}), max_x = std::max({v[0].x, v[1].x, v[2].x});
  const double min_y = std::min({v[0].y, v[1].y, v[2].y}), max_y = std::max({v[0].y, v[1].y, v[2].y});
  // Clamp in double first so huge coordinates never overflow the int
  // conversion; a NaN box compares false and is dropped.
  if (!(max_x >= 0 && min_x <= double(w) - 1 && max_y >= 0 && min_y <= double(h) - 1)) return false;
  *i0 = int(std::ceil(std::max(min_x, 0.0)));
  *i1 = int(std::floor(std::min(max_x, double(w) - 1)));
  *j0 = int(std::ceil(std::max(min_y, 0.0)));
  *j1 = int(std::floor(std::min(max_y, double(h) - 1)));
  return *i0 <= *i1 && *j0 <= *j1;
}

TileBins bin_items(const SweepItems& items, const Topology& topo, const std::vector<ScreenVertex>& sv,
                   const std::vector<NearTriangle>& near, uint32_t width, uint32_t height, uint32_t tile) {
  TileBins b;
  b.cols = (width + tile - 1) / tile;
  b.rows = (height + tile - 1) / tile;
  b.offset.assign(size_t(b.cols) * b.rows + 1, 0);
  // Each item's box in tiles, so the fill pass does not redo the projection.
  struct Box {
    uint32_t c0, c1, r0, r1;
  };
  std::vector<Box> box(items.size());
  for (size_t k = 0; k < items.size(); ++k) {
    ScreenVertex v[3];
    item_triangle(items, k, topo, sv, near, v);
    box[k] = {1, 0, 1, 0};  // empty unless it covers pixel centres
    const double det = screen_det(v);
    if (det == 0 || !std::isfinite(det)) {
      ++b.degenerate;
      continue;
    }
    int i0, i1, j0, j1;
    if (!pixel_range(v, width, height, &i0, &i1, &j0, &j1)) {
      ++b.offscreen;
      continue;
    }
    Box& x = box[k];
    x = {uint32_t(i0) / tile, uint32_t(i1) / tile, uint32_t(j0) / tile, uint32_t(j1) / tile};
    for (uint32_t r = x.r0; r <= x.r1; ++r)
      for (uint32_t c = x.c0; c <= x.c1; ++c) ++b.offset[size_t(r) * b.cols + c + 1];
  }
  for (size_t t = 1; t < b.offset.size(); ++t) b.offset[t] += b.offset[t - 1];
  b.items.resize(b.offset.back());
  std::vector<uint64_t> fill(b.offset.begin(), b.offset.end() - 1);
  for (size_t k = 0; k < items.size(); ++k) {
    const Box& x = box[k];
    if (x.c0 > x.c1) continue;
    for (uint32_t r = x.r0; r <= x.r1; ++r)
      for (uint32_t c = x.c0; c <= x.c1; ++c) b.items[fill[size_t(r) * b.cols + c]++] = uint32_t(k);
  }
  return b;
}

}  // namespace zs
