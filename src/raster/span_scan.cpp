#include "raster/span_scan.h"

#include <algorithm>
#include <cmath>

namespace zs {

// Faces whose candidate box is at most this many pixels are tested directly.
constexpr int64_t kDirectTestPixels = 12;

void scan_span(const ScreenTriangle& t, const Viewport& vp, FaceFragments& out, ScanCounters& c) {
  const int j0 = std::max(vp.y0, int(std::ceil(std::clamp(t.min_y, double(vp.y0) - 1, double(vp.y1) + 1))));
  const int j1 = std::min(vp.y1 - 1, int(std::floor(std::clamp(t.max_y, double(vp.y0) - 1, double(vp.y1) + 1))));
  const size_t before = out.size();
  if (j0 > j1) return;
  // Tiny faces (most faces of a fine mesh at low resolution): solving for the
  // span ends costs more than testing the few candidates. Same predicate, so
  // the same fragments either way.
  {
    const int i0 = std::max(vp.x0, int(std::ceil(std::clamp(t.min_x, double(vp.x0) - 1, double(vp.x1) + 1))));
    const int i1 = std::min(vp.x1 - 1, int(std::floor(std::clamp(t.max_x, double(vp.x0) - 1, double(vp.x1) + 1))));
    if (i0 > i1) return;
    if (int64_t(i1 - i0 + 1) * int64_t(j1 - j0 + 1) <= kDirectTestPixels) {
      uint64_t tested = 0;
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          ++tested;
          if (!t.inside(i, j)) continue;
          double z, s;
          t.attributes(i, j, &z, &s);
          out.push(i, j, z, s);
        }
      c.pixel_tests += tested;
      c.pixel_hits += out.size() - before;
      c.pixel_misses += tested - (out.size() - before);
      return;
    }
  }
  // Per edge, X where sign·E = 0 on row j is ax + (j - ay)·dx/dy: a multiply
  // per row (the ends are checked exactly below, so rounding here is harmless).
  double inv_slope[3];
  for (int k = 0; k < 3; ++k) inv_slope[k] = t.edge[k].dy != 0 ? t.edge[k].dx / t.edge[k].dy : 0.0;
  uint64_t tests = 0, fails = 0;
  auto inside = [&](int i, int j) {
    ++tests;
    const bool in = t.inside(i, j);
    fails += !in;
    return in;
  };
  for (int j = j0; j <= j1; ++j) {
    // Solve sign·E_k(X, j) >= 0 for X: E = dx·(j - ay) - dy·(X - ax).
    double lo = double(vp.x0), hi = double(vp.x1 - 1);
    bool empty = false;
    for (int k = 0; k < 3; ++k) {
      const EdgeFn& e = t.edge[k];
      const double slope = -e.sign * e.dy;  // d(sign·E)/dX
      if (slope == 0) {
        if (!e.inside(0, j)) empty = true;  // constant along the row
        continue;
      }
      const double x0 = e.ax + (double(j) - e.ay) * inv_slope[k];
      if (slope > 0) lo = std::max(lo, x0);
      else hi = std::min(hi, x0);
    }
    if (empty || !(lo <= hi + 1)) continue;
    // Estimated ends; rounding in x0 can be off by one pixel either way.
    int i0 = int(std::ceil(std::max(lo, double(vp.x0)))), i1 = int(std::floor(std::min(hi, double(vp.x1 - 1))));
    if (i0 > i1) {
      // Maybe one pixel hides in the rounding: probe around the estimate.
      int found = INT32_MIN;
      for (int i = std::max(vp.x0, i1 - 1); i <= std::min(vp.x1 - 1, i0 + 1); ++i)
        if (inside(i, j)) {
          found = i;
          break;
        }
      if (found == INT32_MIN) continue;
      i0 = i1 = found;
    }
    // Make the ends exact with the same predicate the bounding box uses.
    if (inside(i0, j)) {
      while (i0 > vp.x0 && inside(i0 - 1, j)) --i0;
    } else {
      while (i0 <= i1 && !inside(i0, j)) ++i0;
      if (i0 > i1) continue;
    }
    if (inside(i1, j)) {
      while (i1 < vp.x1 - 1 && inside(i1 + 1, j)) ++i1;
    } else {
      while (i1 > i0 && !inside(i1, j)) --i1;
    }
    for (int i = i0; i <= i1; ++i) {
      double z, s;
      t.attributes(i, j, &z, &s);
      out.push(i, j, z, s);
    }
  }
  c.pixel_tests += tests;
  c.pixel_misses += fails;
  c.pixel_hits += out.size() - before;
}

}  // namespace zs
