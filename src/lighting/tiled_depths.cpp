#include "lighting/tiled_depths.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "lighting/multi_depth.h"

namespace zs {

void TiledDepths::reset(uint32_t size, uint32_t n) {
  size_ = size;
  n_ = n;
  tiles_ = (size + kMapTile - 1) >> kMapTileShift;
  slot_.assign(size_t(tiles_) * tiles_, kEmptyTile);
  data_.clear();
}

float* TiledDepths::add_tile(uint32_t tx, uint32_t ty) {
  uint32_t& s = slot_[size_t(ty) * tiles_ + tx];
  if (s == kEmptyTile) {
    s = stored_tiles();
    data_.resize(data_.size() + size_t(kMapTile) * kMapTile * n_, INFINITY);
  }
  return tile(tx, ty);
}

uint64_t round_depths_up(const double* z, size_t n, float* out) {
  uint64_t covered = 0;
  for (size_t p = 0; p < n; ++p) {
    // f = float(z), then std::nextafter(f, +inf) where f < z, on the bits
    // (so the loop vectorizes): one ulp up is +1 on a positive float's bits
    // (+0 to the least denormal, the largest float to +inf) and −1 on a
    // negative one's (−denorm_min to −0). f = −0 never rounds up: only a
    // negative z gives it.
    const float f = float(z[p]);
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    const uint32_t step = (bits >> 31) ? 0xffffffffu : 1u;
    bits += double(f) < z[p] ? step : 0u;
    std::memcpy(out + p, &bits, 4);
    covered += z[p] < INFINITY;
  }
  return covered;
}

void TiledDepthsSink::tile(const TileRect& r, const float* px) {
  float* t = c->tile(r.x0 >> kMapTileShift, r.y0 >> kMapTileShift);
  for (uint32_t y = 0; y < r.height(); ++y)
    std::memcpy(t + size_t(y) * kMapTile, px + size_t(y) * r.width(), r.width() * sizeof(float));
}

void tile_depths(const float* z, uint32_t size, TiledDepths* out) {
  out->reset(size, 1);
  for (uint32_t ty = 0; ty < out->tiles(); ++ty)
    for (uint32_t tx = 0; tx < out->tiles(); ++tx) {
      const uint32_t x0 = tx * kMapTile, y0 = ty * kMapTile;
      const uint32_t x1 = std::min(size, x0 + kMapTile), y1 = std::min(size, y0 + kMapTile);
      bool any = false;
      for (uint32_t y = y0; y < y1 && !any; ++y)
        for (uint32_t x = x0; x < x1; ++x) any |= z[size_t(y) * size + x] < INFINITY;
      if (!any) continue;
      float* t = out->add_tile(tx, ty);
      for (uint32_t y = y0; y < y1; ++y)
        std::copy(z + size_t(y) * size + x0, z + size_t(y) * size + x1, t + size_t(y - y0) * kMapTile);
    }
}

void tiled_multi_depth(const TiledDepths& centre, uint32_t n, DepthSelect select, TiledDepths* out) {
  const uint32_t T = centre.tiles(), S = centre.size();
  out->reset(S, n);
  // Stored tiles and their neighbours, allocated in row-major order.
  std::vector<std::pair<uint32_t, uint32_t>> need;
  for (uint32_t ty = 0; ty < T; ++ty)
    for (uint32_t tx = 0; tx < T; ++tx) {
      bool near = false;
      for (uint32_t j = ty ? ty - 1 : 0; j <= std::min(T - 1, ty + 1); ++j)
        for (uint32_t i = tx ? tx - 1 : 0; i <= std::min(T - 1, tx + 1); ++i) near |= centre.stored(i, j);
      if (near) need.push_back({tx, ty});
    }
  out->reserve_tiles(need.size());
  for (const auto& [tx, ty] : need) out->add_tile(tx, ty);
  // Each tile from its apron (the tile and a one-texel rim), clamped at the
  // map's border as build_multi_depth clamps; inside the apron no texel
  // needs a clamp. The 3×3 maximum and minimum are separable: rows, then
  // columns (no NaN is ever stored, so the order of max and min is free).
  constexpr uint32_t A = kMapTile + 2;
  std::vector<float> apron(size_t(A) * A), hmax(size_t(A) * kMapTile), hmin(size_t(A) * kMapTile);
  const std::vector<std::pair<int, int>> pat = n >= 4 ? depth_pattern(n) : std::vector<std::pair<int, int>>{};
  for (uint32_t ty = 0; ty < T; ++ty)
    for (uint32_t tx = 0; tx < T; ++tx) {
      if (!out->stored(tx, ty)) continue;
      const int x0 = int(tx * kMapTile) - 1, y0 = int(ty * kMapTile) - 1;
      for (uint32_t j = 0; j < A; ++j) {
        const uint32_t y = uint32_t(std::clamp(y0 + int(j), 0, int(S) - 1));
        float* row = apron.data() + size_t(j) * A;
        // The tile's own texels of map row y, one run; the rim texel by texel.
        const float* src = centre.row(tx, y);
        if (src)
          std::copy(src, src + kMapTile, row + 1);
        else
          std::fill(row + 1, row + 1 + kMapTile, INFINITY);
        row[0] = centre.texel(uint32_t(std::max(x0, 0)), y)[0];
        row[A - 1] = centre.texel(uint32_t(std::min(x0 + int(A) - 1, int(S) - 1)), y)[0];
        // Columns past the map's edge (a partial last tile) read its last texel.
        for (uint32_t i = 1; i + 1 < A; ++i)
          if (x0 + int(i) > int(S) - 1) row[i] = centre.texel(S - 1, y)[0];
      }
      const float* a = apron.data();
      float* t = out->tile(tx, ty);
      if (n >= 4) {
        for (uint32_t y = 0; y < kMapTile; ++y)
          for (uint32_t x = 0; x < kMapTile; ++x) {
            float* o = t + (size_t(y) * kMapTile + x) * n;
            o[0] = a[size_t(y + 1) * A + x + 1];
            for (uint32_t i = 0; i + 1 < n; ++i)
              o[i + 1] = a[size_t(int(y) + 1 + pat[i].second) * A + size_t(int(x) + 1 + pat[i].first)];
          }
        continue;
      }
      for (uint32_t j = 0; j < A; ++j) {
        const float* r = a + size_t(j) * A;
        for (uint32_t x = 0; x < kMapTile; ++x) {
          hmax[size_t(j) * kMapTile + x] = std::max(std::max(r[x], r[x + 1]), r[x + 2]);
          hmin[size_t(j) * kMapTile + x] = std::min(std::min(r[x], r[x + 1]), r[x + 2]);
        }
      }
      for (uint32_t y = 0; y < kMapTile; ++y)
        for (uint32_t x = 0; x < kMapTile; ++x) {
          const size_t h = size_t(y) * kMapTile + x;
          const float mx = std::max(std::max(hmax[h], hmax[h + kMapTile]), hmax[h + 2 * kMapTile]);
          const float mn = std::min(std::min(hmin[h], hmin[h + kMapTile]), hmin[h + 2 * kMapTile]);
          float* o = t + h * n;
          o[0] = a[size_t(y + 1) * A + x + 1];
          if (n == 2) {
            o[1] = select == DepthSelect::Max ? mx : mn;
          } else {
            o[1] = mx;
            o[2] = mn;
          }
        }
    }
}

}  // namespace zs
