#include "raster/bbox_scan.h"

#include <algorithm>
#include <cmath>

namespace zs {

void scan_bbox(const ScreenTriangle& t, const Viewport& vp, FaceSpans& out, ScanCounters& c) {
  // Pixel centres are at integer coordinates. Clamp in double first so huge
  // coordinates never overflow the int conversion.
  auto lo = [](double v, int a, int b) { return int(std::ceil(std::clamp(v, double(a) - 1, double(b) + 1))); };
  auto hi = [](double v, int a, int b) { return int(std::floor(std::clamp(v, double(a) - 1, double(b) + 1))); };
  const int i0 = std::max(vp.x0, lo(t.min_x, vp.x0, vp.x1));
  const int i1 = std::min(vp.x1 - 1, hi(t.max_x, vp.x0, vp.x1));
  const int j0 = std::max(vp.y0, lo(t.min_y, vp.y0, vp.y1));
  const int j1 = std::min(vp.y1 - 1, hi(t.max_y, vp.y0, vp.y1));
  if (i0 > i1 || j0 > j1) return;
  uint64_t hits = 0;
  for (int j = j0; j <= j1; ++j) {
    // Every pixel is tested; the hits form one run per row (screen_triangle.h),
    // but runs are closed wherever a miss follows a hit all the same.
    int first = -1;
    for (int i = i0; i <= i1; ++i) {
      if (t.inside(i, j)) {
        if (first < 0) first = i;
        continue;
      }
      if (first >= 0) out.push(j, first, i - 1), hits += uint64_t(i - first), first = -1;
    }
    if (first >= 0) out.push(j, first, i1), hits += uint64_t(i1 - first + 1);
  }
  const uint64_t tested = uint64_t(i1 - i0 + 1) * uint64_t(j1 - j0 + 1);
  c.pixel_tests += tested;
  c.pixel_hits += hits;
  c.pixel_misses += tested - hits;
}

}  // namespace zs
