// The pixels of a tile a sphere covers, each with its exact ray hit: the
// translucent modes' loop (the opaque renderer has its own, fused with its
// depth buffer). Small boxes are tried pixel by pixel; larger ones get a
// lower bound of the sphere's depth per 8×8 block (sphere_depth_bound), so
// blocks and pixels whose threshold lies in front of it are skipped before
// any exact hit, and the rest is scanned as one exact run per row
// (raster/sphere_span.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "raster/sphere_span.h"
#include "render/spheres/sphere_stats.h"
#include "render/spheres/sphere_visibility.h"

namespace zs {

constexpr int kTileBlock = 8;          // pixels per side of a tile block
constexpr int kBoundMinBlocks = 4;     // boxes spanning fewer blocks use the sphere's nearest depth only

// The largest of a per-pixel array over each kTileBlock² block of a tile,
// recomputed lazily for blocks marked since.
class BlockMax {
 public:
  void reset(uint32_t w, uint32_t h) {
    w_ = w, h_ = h, bw_ = (w + kTileBlock - 1) / kTileBlock;
    const size_t n = size_t(bw_) * ((h + kTileBlock - 1) / kTileBlock);
    max_.assign(n, 0.0);
    dirty_.assign(n, 1);
  }
  void mark(size_t p) { dirty_[size_t(p / w_ / kTileBlock) * bw_ + (p % w_) / kTileBlock] = 1; }
  void mark_all() { std::fill(dirty_.begin(), dirty_.end(), 1); }
  double get(const double* v, int bx, int by) {
    const size_t b = size_t(by) * bw_ + size_t(bx);
    if (dirty_[b]) {
      double m = -INFINITY;
      const uint32_t y1 = std::min<uint32_t>(h_, uint32_t(by + 1) * kTileBlock);
      const uint32_t x1 = std::min<uint32_t>(w_, uint32_t(bx + 1) * kTileBlock);
      for (uint32_t y = uint32_t(by) * kTileBlock; y < y1; ++y)
        for (uint32_t x = uint32_t(bx) * kTileBlock; x < x1; ++x) m = std::max(m, v[size_t(y) * w_ + x]);
      max_[b] = m;
      dirty_[b] = 0;
    }
    return max_[b];
  }

 private:
  uint32_t w_ = 0, h_ = 0, bw_ = 0;
  std::vector<double> max_;
  std::vector<uint8_t> dirty_;
};

// Two thresholds per pixel: fragments behind `gone` can never count (an
// opaque surface in front, or the pixel done: -inf), fragments behind `now`
// cannot count in this pass (gone, or the pass's own limit). A sphere is
// skipped where its depth bound lies behind them.
struct PixelThresholds {
  const double* gone;
  const double* now;
  BlockMax* gone_max;
  BlockMax* now_max;
};

// Calls fn(p, hit) for every pixel of `vp` (p = row-major index in the tile)
// whose ray hits the sphere and where it may be in front of the pixel's
// `now` threshold. Returns true when it skipped a pixel whose `now` but not
// `gone` threshold hid the sphere there (the sphere may count in a later
// pass). [i0, i1] × [j0, j1]: the sphere's pixel range in tile coordinates;
// z_reject: a lower bound of every depth sphere_hit gives for it.
template <class Fn>
bool for_each_sphere_hit(const SphereSetup& su, const Viewport& vp, int i0, int i1, int j0, int j1, double z_reject,
                         const PixelThresholds& th, std::vector<double>& zlow, FaceSpans& spans, SphereStats& S,
                         Fn&& fn) {
  const size_t w = size_t(vp.x1 - vp.x0);
  bool deferred = false;
  // A pixel (or block) with bound zl: 0 visit, 1 skip for good, 2 skip for now.
  auto pixel = [&](size_t p, double zl) {
    if (th.now[p] >= zl) return false;
    ++S.early_rejected;
    if (th.gone[p] >= zl) deferred = true;
    return true;
  };
  if ((i1 - i0 + 1) * (j1 - j0 + 1) <= kSmallSphereBox) {
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t p = size_t(j) * w + size_t(i);
        if (pixel(p, z_reject)) continue;
        ++S.pixel_tests;
        SphereHit h;
        if (!sphere_hit(su, double(i + vp.x0), double(j + vp.y0), &h)) continue;
        ++S.fragments;
        fn(p, h);
      }
    return deferred;
  }
  // Per block of the box: the nearest the sphere can be there, +inf where
  // every pixel's threshold is in front of it.
  const int bx0 = i0 / kTileBlock, by0 = j0 / kTileBlock;
  const int nbx = i1 / kTileBlock - bx0 + 1, nby = j1 / kTileBlock - by0 + 1;
  const bool bounds = nbx * nby >= kBoundMinBlocks;
  zlow.resize(size_t(nbx) * size_t(nby));
  int row0 = nby, row1 = -1;
  for (int by = 0; by < nby; ++by)
    for (int bx = 0; bx < nbx; ++bx) {
      double zl = z_reject;
      const double now_max = th.now_max->get(th.now, bx0 + bx, by0 + by);
      // The bound only where it can hide something: a block with a pixel
      // open to any depth is visited whatever it is.
      if (bounds && now_max >= z_reject && now_max != INFINITY) {
        const int px = (bx0 + bx) * kTileBlock, py = (by0 + by) * kTileBlock;
        const double X0 = px + vp.x0, X1 = std::min<int>(px + kTileBlock, int(w)) - 1 + vp.x0;
        const double Y0 = py + vp.y0, Y1 = std::min<int>(py + kTileBlock, vp.y1 - vp.y0) - 1 + vp.y0;
        zl = std::max(z_reject, sphere_depth_bound(su, X0, X1, Y0, Y1));
      }
      bool hidden = false;
      if (now_max < zl) {
        hidden = true;
        if (!(th.gone_max->get(th.gone, bx0 + bx, by0 + by) < zl)) deferred = true;
      }
      zlow[size_t(by) * nbx + bx] = hidden ? INFINITY : zl;
      if (!hidden) row0 = std::min(row0, by), row1 = by;
    }
  if (row1 < 0) {
    ++S.spheres_block_rejected;
    return deferred;
  }
  const Viewport rows{vp.x0, vp.y0 + (by0 + row0) * kTileBlock, vp.x1,
                      std::min(vp.y1, vp.y0 + (by0 + row1 + 1) * kTileBlock)};
  spans.clear();
  ScanCounters sc;
  scan_sphere(su, rows, spans, sc);
  S.pixel_tests += sc.pixel_tests;
  for (const RowSpan& row : spans.rows) {
    const int y = row.y - vp.y0;
    const size_t base = size_t(y) * w;
    const double* zrow = zlow.data() + size_t(y / kTileBlock - by0) * nbx;
    for (int x = row.x0 - vp.x0, xe = row.x1 - vp.x0; x <= xe;) {
      const int b = x / kTileBlock - bx0, end = std::min(xe, (x / kTileBlock + 1) * kTileBlock - 1);
      const double zl = b >= 0 && b < nbx ? zrow[b] : z_reject;
      if (zl == INFINITY) {
        S.early_rejected += uint64_t(end - x + 1);
        x = end + 1;
        continue;
      }
      for (; x <= end; ++x) {
        const size_t p = base + size_t(x);
        if (pixel(p, zl)) continue;
        SphereHit h;
        if (!sphere_hit(su, double(x + vp.x0), double(row.y), &h)) continue;
        ++S.fragments;
        fn(p, h);
      }
    }
  }
  return deferred;
}

}  // namespace zs
