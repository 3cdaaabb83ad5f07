#include "raster/span_scan.h"

#include <algorithm>
#include <cmath>

namespace zs {

namespace {

// Faces whose candidate box is at most this many pixels are tested directly.
constexpr int64_t kDirectTestPixels = 12;

// The pixel range of row Y inside edge e, clamped to [x0, x1) (empty: lo > hi).
// sign·E is monotone along the row, so the inside set is a half-line: solve
// for its end, then step to the exact end with e's own inside test.
// `tests`/`fails` count the single-edge tests made.
struct EdgeTests {
  uint64_t tests = 0, fails = 0;
  bool operator()(const EdgeFn& e, int X, int Y) {
    const bool in = e.inside(X, Y);
    ++tests;
    fails += !in;
    return in;
  }
};

inline void edge_limit(const EdgeFn& e, double inv_slope, int Y, int x0, int x1, int* lo, int* hi, EdgeTests& in) {
  const double slope = -e.sign * e.dy;  // d(sign·E)/dX
  if (slope == 0) {
    if (!in(e, 0, Y)) *lo = x1, *hi = x0 - 1;  // constant along the row
    return;
  }
  // Where sign·E = 0: ax + (Y - ay)·dx/dy, clamped before the int conversion.
  const double root = std::clamp(e.ax + (double(Y) - e.ay) * inv_slope, double(x0) - 1, double(x1));
  if (slope > 0) {  // inside from some X on
    int c = int(std::ceil(root));
    if (c > x0 && in(e, c - 1, Y)) {
      do --c;
      while (c > x0 && in(e, c - 1, Y));
    } else {
      while (c < x1 && !in(e, c, Y)) ++c;
    }
    *lo = std::max(*lo, c);
  } else {  // inside up to some X
    int c = int(std::floor(root));
    if (c < x1 - 1 && in(e, c + 1, Y)) {
      do ++c;
      while (c < x1 - 1 && in(e, c + 1, Y));
    } else {
      while (c >= x0 && !in(e, c, Y)) --c;
    }
    *hi = std::min(*hi, c);
  }
}

}  // namespace

void scan_span(const ScreenTriangle& t, const Viewport& vp, FaceSpans& out, ScanCounters& c) {
  const int j0 = std::max(vp.y0, int(std::ceil(std::clamp(t.min_y, double(vp.y0) - 1, double(vp.y1) + 1))));
  const int j1 = std::min(vp.y1 - 1, int(std::floor(std::clamp(t.max_y, double(vp.y0) - 1, double(vp.y1) + 1))));
  if (j0 > j1) return;
  const int i0 = std::max(vp.x0, int(std::ceil(std::clamp(t.min_x, double(vp.x0) - 1, double(vp.x1) + 1))));
  const int i1 = std::min(vp.x1 - 1, int(std::floor(std::clamp(t.max_x, double(vp.x0) - 1, double(vp.x1) + 1))));
  if (i0 > i1) return;
  uint64_t hits = 0;
  // Tiny faces (most faces of a fine mesh at low resolution): solving for the
  // span ends costs more than testing the few candidates. Same predicate, so
  // the same pixels either way.
  if (int64_t(i1 - i0 + 1) * int64_t(j1 - j0 + 1) <= kDirectTestPixels) {
    for (int j = j0; j <= j1; ++j) {
      int first = i1 + 1, last = i0 - 1;
      for (int i = i0; i <= i1; ++i)
        if (t.inside(i, j)) first = std::min(first, i), last = i;
      if (first <= last) {
        out.push(j, first, last);
        hits += uint64_t(last - first + 1);
      }
    }
    const uint64_t tested = uint64_t(i1 - i0 + 1) * uint64_t(j1 - j0 + 1);
    c.pixel_tests += tested;
    c.pixel_hits += hits;
    c.pixel_misses += tested - hits;
    return;
  }
  double inv_slope[3];
  for (int k = 0; k < 3; ++k) inv_slope[k] = t.edge[k].dy != 0 ? t.edge[k].dx / t.edge[k].dy : 0.0;
  // Within the face's box: the exact ends never lie outside it.
  const int x0 = i0, x1 = i1 + 1;
  EdgeTests in;
  for (int j = j0; j <= j1; ++j) {
    int lo = x0, hi = x1 - 1;
    for (int k = 0; k < 3 && lo <= hi; ++k) edge_limit(t.edge[k], inv_slope[k], j, x0, x1, &lo, &hi, in);
    if (lo > hi) continue;
    out.push(j, lo, hi);
    hits += uint64_t(hi - lo + 1);
  }
  // The end searches test single edges: counted in pixel tests (three edges).
  c.pixel_tests += (in.tests + 2) / 3;
  c.pixel_misses += (in.fails + 2) / 3;
  c.pixel_hits += hits;
}

}  // namespace zs
