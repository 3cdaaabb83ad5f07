// The pixels of a tile a sphere covers, each with its exact ray hit: the
// translucent modes' loop (the opaque renderer has its own, with per-block
// depth bounds). Small boxes are tried pixel by pixel, larger ones scanned
// as one exact run per row (raster/sphere_span.h).
#pragma once

#include "raster/sphere_span.h"
#include "sprites/sphere_stats.h"
#include "sprites/sphere_visibility.h"

namespace zs {

// Calls fn(p, hit) for every pixel of `vp` (p = row-major index in the
// tile) whose ray hits the sphere, except where skip(p) — asked before the
// exact hit — is true. [i0, i1] × [j0, j1]: the sphere's pixel range in tile
// coordinates (sphere_pixel_range, shifted).
template <class Skip, class Fn>
void for_each_sphere_hit(const SphereSetup& su, const Viewport& vp, int i0, int i1, int j0, int j1,
                         FaceSpans& spans, SphereStats& S, Skip&& skip, Fn&& fn) {
  const size_t w = size_t(vp.x1 - vp.x0);
  if ((i1 - i0 + 1) * (j1 - j0 + 1) <= kSmallSphereBox) {
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t p = size_t(j) * w + size_t(i);
        if (skip(p)) {
          ++S.early_rejected;
          continue;
        }
        ++S.pixel_tests;
        SphereHit h;
        if (!sphere_hit(su, double(i + vp.x0), double(j + vp.y0), &h)) continue;
        ++S.fragments;
        fn(p, h);
      }
    return;
  }
  const Viewport rows{vp.x0, vp.y0 + j0, vp.x1, vp.y0 + j1 + 1};
  spans.clear();
  ScanCounters sc;
  scan_sphere(su, rows, spans, sc);
  S.pixel_tests += sc.pixel_tests;
  for (const RowSpan& row : spans.rows) {
    const size_t base = size_t(row.y - vp.y0) * w;
    for (int x = row.x0; x <= row.x1; ++x) {
      const size_t p = base + size_t(x - vp.x0);
      if (skip(p)) {
        ++S.early_rejected;
        continue;
      }
      SphereHit h;
      if (!sphere_hit(su, double(x), double(row.y), &h)) continue;
      ++S.fragments;
      fn(p, h);
    }
  }
}

}  // namespace zs
