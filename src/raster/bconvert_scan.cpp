#include "raster/bconvert_scan.h"

#include <algorithm>
#include <cmath>

namespace zs {

const char* to_string(BConvertVariant v) {
  switch (v) {
    case BConvertVariant::Truncate: return "truncate";
    case BConvertVariant::Round: return "round";
    case BConvertVariant::Dilate: return "dilate";
    case BConvertVariant::Dda3d: return "dda3d";
    case BConvertVariant::RunLength: return "runlength";
  }
  return "?";
}

bool parse_bconvert_variant(const std::string& s, BConvertVariant* out) {
  for (BConvertVariant v : {BConvertVariant::Truncate, BConvertVariant::Round, BConvertVariant::Dilate,
                            BConvertVariant::Dda3d, BConvertVariant::RunLength})
    if (s == to_string(v)) return *out = v, true;
  return false;
}

bool bconvert_list(const ScreenVertex v[3], BConvertVariant variant, const Viewport& vp, BConvertScratch& s) {
  double lo_x = v[0].x, hi_x = v[0].x, lo_y = v[0].y, hi_y = v[0].y;
  for (int k = 1; k < 3; ++k) {
    lo_x = std::min(lo_x, v[k].x), hi_x = std::max(hi_x, v[k].x);
    lo_y = std::min(lo_y, v[k].y), hi_y = std::max(hi_y, v[k].y);
  }
  // The seed maps the whole dataset into the image; faces reaching far out of
  // the viewport (perspective close-ups) would make edge lists huge.
  const double w = vp.x1 - vp.x0, h = vp.y1 - vp.y0;
  if (lo_x < vp.x0 - 4 * w - 16 || hi_x > vp.x1 + 4 * w + 16 || lo_y < vp.y0 - 4 * h - 16 ||
      hi_y > vp.y1 + 4 * h + 16)
    return false;
  if (variant == BConvertVariant::Dda3d) {
    const double x[3] = {v[0].x, v[1].x, v[2].x}, y[3] = {v[0].y, v[1].y, v[2].y};
    build_compact_list_dda(x, y, s.list);
    return true;
  }
  // w2sX truncates (the pixel whose sample point is at or before x); w2sXr rounds.
  auto to_pixel = [&](double c) {
    return int32_t(variant == BConvertVariant::Round ? std::floor(c + 0.5) : std::floor(c));
  };
  const IPoint p[3] = {{to_pixel(v[0].x), to_pixel(v[0].y)},
                       {to_pixel(v[1].x), to_pixel(v[1].y)},
                       {to_pixel(v[2].x), to_pixel(v[2].y)}};
  build_compact_list(p[0], p[1], p[2], variant == BConvertVariant::RunLength ? EdgeWalker::RunLength : EdgeWalker::Bresenham,
                     s.edges, s.list);
  if (variant == BConvertVariant::Dilate)
    for (size_t r = 0; r < s.list.xi.size(); ++r) --s.list.xi[r], ++s.list.xf[r];
  return true;
}

void bconvert_scan(const ScreenTriangle& t, const Viewport& vp, BConvertScratch& s, FaceSpans& out,
                   ScanCounters& c, RowEndMisses* row_ends) {
  const CompactList& L = s.list;
  uint64_t tested = 0, hits = 0;
  const int32_t j0 = std::max(L.y0, int32_t(vp.y0)), j1 = std::min(L.y1, int32_t(vp.y1 - 1));
  for (int32_t j = j0; j <= j1; ++j) {
    const size_t r = size_t(j - L.y0);
    const int32_t i0 = std::max(L.xi[r], int32_t(vp.x0)), i1 = std::min(L.xf[r], int32_t(vp.x1 - 1));
    if (i0 > i1) continue;
    tested += uint64_t(i1 - i0 + 1);
    // The hits of a candidate run are one run (screen_triangle.h); runs are
    // closed wherever a miss follows a hit all the same.
    int32_t first = -1, last = -1, run = -1;
    for (int32_t i = i0; i <= i1; ++i) {
      if (!t.inside(i, j)) {
        if (run >= 0) out.push(j, run, i - 1), hits += uint64_t(i - run), run = -1;
        continue;
      }
      if (run < 0) run = i;
      if (first < 0) first = i;
      last = i;
    }
    if (run >= 0) out.push(j, run, i1), hits += uint64_t(i1 - run + 1);
    if (row_ends) {
      if (first < 0) {
        row_ends->add(uint64_t(i1 - i0 + 1));
      } else {
        row_ends->add(uint64_t(first - i0));
        row_ends->add(uint64_t(i1 - last));
      }
    }
  }
  c.pixel_tests += tested;
  c.pixel_hits += hits;
  c.pixel_misses += tested - hits;
}

}  // namespace zs
