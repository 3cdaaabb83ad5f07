#include "raster/bbox_scan.h"

#include <algorithm>
#include <cmath>

namespace zs {

void scan_bbox(const ScreenTriangle& t, const Viewport& vp, FaceFragments& out, ScanCounters& c) {
  // Pixel centres are at integer coordinates. Clamp in double first so huge
  // coordinates never overflow the int conversion.
  auto lo = [](double v, int a, int b) { return int(std::ceil(std::clamp(v, double(a) - 1, double(b) + 1))); };
  auto hi = [](double v, int a, int b) { return int(std::floor(std::clamp(v, double(a) - 1, double(b) + 1))); };
  const int i0 = std::max(vp.x0, lo(t.min_x, vp.x0, vp.x1));
  const int i1 = std::min(vp.x1 - 1, hi(t.max_x, vp.x0, vp.x1));
  const int j0 = std::max(vp.y0, lo(t.min_y, vp.y0, vp.y1));
  const int j1 = std::min(vp.y1 - 1, hi(t.max_y, vp.y0, vp.y1));
  if (i0 > i1 || j0 > j1) return;
  const size_t before = out.size();
  c.pixel_tests += uint64_t(i1 - i0 + 1) * uint64_t(j1 - j0 + 1);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      if (!t.inside(i, j)) continue;
      double z, s;
      t.attributes(i, j, &z, &s);
      out.push(i, j, z, s);
    }
  }
  c.pixel_hits += out.size() - before;
  c.pixel_misses += uint64_t(i1 - i0 + 1) * uint64_t(j1 - j0 + 1) - (out.size() - before);
}

}  // namespace zs
