#include "raster/compact_list.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace zs {

namespace {

void walk(EdgeWalker w, IPoint a, IPoint b, std::vector<int32_t>& out) {
  if (w == EdgeWalker::RunLength) runlength_edge_pairs(a, b, out);
  else bresenham_edge_pairs(a, b, out);
}

// One row's span from lists A (row ka) and B (row kb).
inline void span(const std::vector<int32_t>& A, size_t ka, const std::vector<int32_t>& B, size_t kb, bool tie_to_a,
                 int32_t* xi, int32_t* xf) {
  const int32_t amin = A[2 * ka], bmin = B[2 * kb];
  if (amin < bmin || (amin == bmin && tie_to_a)) {
    *xi = amin;
    *xf = B[2 * kb + 1];
  } else {
    *xi = bmin;
    *xf = A[2 * ka + 1];
  }
}

}  // namespace

void build_compact_list(IPoint v0, IPoint v1, IPoint v2, EdgeWalker walker, CompactScratch& s, CompactList& out) {
  // Sort by y (then x, so the order is deterministic).
  auto less = [](IPoint a, IPoint b) { return a.y < b.y || (a.y == b.y && a.x < b.x); };
  if (less(v1, v0)) std::swap(v0, v1);
  if (less(v2, v1)) std::swap(v1, v2);
  if (less(v1, v0)) std::swap(v0, v1);
  out.y0 = v0.y;
  out.y1 = v2.y;
  out.xi.clear();
  out.xf.clear();
  if (v0.y == v2.y) {  // case 1: one row
    out.xi.push_back(std::min({v0.x, v1.x, v2.x}));
    out.xf.push_back(std::max({v0.x, v1.x, v2.x}));
    return;
  }
  walk(walker, v0, v1, s.l0);
  walk(walker, v1, v2, s.l1);
  walk(walker, v0, v2, s.l2);
  // v1 right of l2 <=> cross < 0 (rows grow downwards; v2.y > v0.y here).
  const int64_t cross = int64_t(v2.x - v0.x) * (v1.y - v0.y) - int64_t(v2.y - v0.y) * (v1.x - v0.x);
  const bool right = cross <= 0;
  const size_t n0 = size_t(v1.y - v0.y);
  out.xi.resize(size_t(v2.y - v0.y + 1));
  out.xf.resize(out.xi.size());
  // Loop A: rows v0.y .. v1.y from l2 and l0.
  for (size_t k = 0; k <= n0; ++k) span(s.l2, k, s.l0, k, right, &out.xi[k], &out.xf[k]);
  // Junction row v1.y: also l1's first pair; widen only if needed.
  int32_t a, b;
  span(s.l2, n0, s.l1, 0, right, &a, &b);
  out.xi[n0] = std::min(out.xi[n0], a);
  out.xf[n0] = std::max(out.xf[n0], b);
  // Loop B: rows v1.y+1 .. v2.y from l2 and l1.
  const size_t n1 = size_t(v2.y - v1.y);
  for (size_t k = 1; k <= n1; ++k) span(s.l2, n0 + k, s.l1, k, right, &out.xi[n0 + k], &out.xf[n0 + k]);
}

void build_compact_list_dda(const double x[3], const double y[3], CompactList& out) {
  auto rnd = [](double v) { return int32_t(std::floor(v + 0.5)); };
  int32_t ylo = rnd(y[0]), yhi = ylo;
  for (int k = 1; k < 3; ++k) ylo = std::min(ylo, rnd(y[k])), yhi = std::max(yhi, rnd(y[k]));
  out.y0 = ylo;
  out.y1 = yhi;
  out.xi.assign(size_t(yhi - ylo + 1), INT32_MAX);
  out.xf.assign(size_t(yhi - ylo + 1), INT32_MIN);
  auto put = [&](double px, double py) {
    const int32_t r = std::clamp(rnd(py), ylo, yhi) - ylo, c = rnd(px);
    out.xi[size_t(r)] = std::min(out.xi[size_t(r)], c);
    out.xf[size_t(r)] = std::max(out.xf[size_t(r)], c);
  };
  for (int e = 0; e < 3; ++e) {
    const double ax = x[e], ay = y[e], bx = x[(e + 1) % 3], by = y[(e + 1) % 3];
    // Eq. 3.1: per-axis steps; the driving axis has the most pixels.
    const int64_t nx = std::llabs(int64_t(rnd(bx)) - rnd(ax)), ny = std::llabs(int64_t(rnd(by)) - rnd(ay));
    const int64_t n = std::max(nx, ny) + 1;
    const double sx = (bx - ax) / double(n), sy = (by - ay) / double(n);
    for (int64_t k = 0; k < n; ++k) put(ax + double(k) * sx, ay + double(k) * sy);
    put(bx, by);  // the final sample at the end point
  }
  // Every row is crossed by the closed boundary; guard anyway.
  for (size_t r = 0; r < out.xi.size(); ++r)
    if (out.xi[r] > out.xf[r]) out.xi[r] = 1, out.xf[r] = 0;
}

}  // namespace zs
