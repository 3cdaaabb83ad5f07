#include "raster/zbuffer_tile.h"

#include "raster/span_scan.h"

namespace zs {

void zbuffer_triangles(const std::vector<ScreenVertex>& verts, const std::vector<std::array<uint32_t, 3>>& corners,
                       const uint32_t* ids, size_t n, bool perspective, const Viewport& vp, DepthBuffer& db,
                       ZBufferScratch& scratch, ZBufferCounts* counts) {
  ZBufferCounts c;
  const size_t w = size_t(vp.x1 - vp.x0);
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
      const size_t row = size_t(r.y - vp.y0) * w - size_t(vp.x0);
      c.fragments += uint64_t(r.x1 - r.x0 + 1);
      for (int32_t x = r.x0; x <= r.x1; ++x) {
        double z, s;
        st.attributes(x, r.y, &z, &s);
        c.depth_writes += db.test_write(row + size_t(x), z, t);
      }
    }
  }
  *counts += c;
}

}  // namespace zs
