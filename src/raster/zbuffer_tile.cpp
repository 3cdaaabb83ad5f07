#include "raster/zbuffer_tile.h"

#include <algorithm>

#include "raster/span_scan.h"

namespace zs {

namespace {

// Sets up and scans each triangle ids[0..n), calling row(t, st, span) for
// every span of pixel centres it covers in `vp`; counts triangles,
// degenerate ones and fragments. Shared by both kernels below.
template <class Row>
void scan_triangles(const std::vector<ScreenVertex>& verts, const std::vector<std::array<uint32_t, 3>>& corners,
                    const uint32_t* ids, size_t n, bool perspective, const Viewport& vp, ZBufferScratch& scratch,
                    ZBufferCounts& c, Row&& row) {
  for (size_t k = 0; k < n; ++k) {
    const uint32_t t = ids[k];
    const ScreenVertex v[3] = {verts[corners[t][0]], verts[corners[t][1]], verts[corners[t][2]]};
    ScreenTriangle st;
    if (!setup_triangle(v, perspective, &st)) {
      ++c.degenerate;
      continue;
    }
    ++c.triangles;
    scratch.spans.clear();
    scan_span(st, vp, scratch.spans, scratch.scan);
    for (const RowSpan& r : scratch.spans.rows) {
      c.fragments += uint64_t(r.x1 - r.x0 + 1);
      row(t, st, r);
    }
  }
}

// The depth at pixel x of row y (qy = the row's term, hoisted): the same
// expression as ScreenTriangle::attributes, clamped as it clamps (NaN stays
// NaN and never wins), −0 stored as +0. Inline in branch-free row loops the
// compiler vectorizes.
template <bool Perspective>
inline double span_depth(const ScreenTriangle& st, double qy, int32_t x) {
  const double q = st.q_c + st.q_gx * (double(x) - st.x0) + qy;
  const double z = Perspective ? 1.0 / q : q;
  return std::min(std::max(z, st.z_lo), st.z_hi) + 0.0;
}

// One row of a span, min-merged into d[x0..x1].
template <bool Perspective>
void min_row(const ScreenTriangle& st, int32_t y, int32_t x0, int32_t x1, double* d) {
  const double qy = st.q_gy * (double(y) - st.y0);
  const int32_t m = x1 - x0;
  for (int32_t i = 0; i <= m; ++i) {
    const double z = span_depth<Perspective>(st, qy, x0 + i);
    d[i] = z < d[i] ? z : d[i];
  }
}

// One row of a span depth-tested into d[x0..x1] / id[x0..x1] by
// DepthBuffer::test_write's rule (nearer, or equal and a smaller or equal
// id); returns the writes.
template <bool Perspective>
uint64_t test_row(const ScreenTriangle& st, int32_t y, int32_t x0, int32_t x1, uint32_t t, double* __restrict d,
                  uint32_t* __restrict id) {
  const double qy = st.q_gy * (double(y) - st.y0);
  const int32_t m = x1 - x0;
  uint64_t writes = 0;
  for (int32_t i = 0; i <= m; ++i) {
    const double z = span_depth<Perspective>(st, qy, x0 + i);
    const bool win = (z < d[i]) | ((z == d[i]) & (t <= id[i]));
    d[i] = win ? z : d[i];
    id[i] = win ? t : id[i];
    writes += win;
  }
  return writes;
}

}  // namespace

void zbuffer_triangles(const std::vector<ScreenVertex>& verts, const std::vector<std::array<uint32_t, 3>>& corners,
                       const uint32_t* ids, size_t n, bool perspective, const Viewport& vp, DepthBuffer& db,
                       ZBufferScratch& scratch, ZBufferCounts* counts) {
  ZBufferCounts c;
  const size_t w = size_t(vp.x1 - vp.x0);
  scan_triangles(verts, corners, ids, n, perspective, vp, scratch, c,
                 [&](uint32_t t, const ScreenTriangle& st, const RowSpan& r) {
                   const size_t at = size_t(r.y - vp.y0) * w + size_t(r.x0 - vp.x0);
                   double* d = db.front_depths() + at;
                   uint32_t* id = db.front_ids() + at;
                   c.depth_writes += perspective ? test_row<true>(st, r.y, r.x0, r.x1, t, d, id)
                                                 : test_row<false>(st, r.y, r.x0, r.x1, t, d, id);
                 });
  *counts += c;
}

void zbuffer_depths(const std::vector<ScreenVertex>& verts, const std::vector<std::array<uint32_t, 3>>& corners,
                    const uint32_t* ids, size_t n, bool perspective, const Viewport& vp, double* depth,
                    ZBufferScratch& scratch, ZBufferCounts* counts) {
  ZBufferCounts c;
  const size_t w = size_t(vp.x1 - vp.x0);
  scan_triangles(verts, corners, ids, n, perspective, vp, scratch, c,
                 [&](uint32_t, const ScreenTriangle& st, const RowSpan& r) {
                   double* row = depth + size_t(r.y - vp.y0) * w + size_t(r.x0 - vp.x0);
                   if (perspective)
                     min_row<true>(st, r.y, r.x0, r.x1, row);
                   else
                     min_row<false>(st, r.y, r.x0, r.x1, row);
                 });
  *counts += c;
}

}  // namespace zs
