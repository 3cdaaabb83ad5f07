// Strategy 2: B-Convert (B-Convert digest §4): integer Bresenham edge lists compacted
// into per-row candidate spans, then the same point-in-triangle test as the
// bounding box on the compact list only. Reproduces the seed's behaviour,
// including its missing ("ausente") pixels.
#pragma once

#include <string>

#include "raster/compact_list.h"
#include "raster/raster_target.h"
#include "raster/screen_triangle.h"

namespace zs {

enum class BConvertVariant {
  Truncate,   // vertices truncated to pixels (w2sX), the seed's default
  Round,      // rounded to the nearest pixel (w2sXr)
  Dilate,     // truncated, every row widened by one pixel each side
  Dda3d,      // the 3-D variant: edges sampled with per-edge steps (Eq. 3.1), bucketed
  RunLength,  // truncated; run-length edge lists (same spans as Truncate, cheaper)
};
const char* to_string(BConvertVariant v);
bool parse_bconvert_variant(const std::string& s, BConvertVariant* out);

struct BConvertScratch {
  CompactScratch edges;
  CompactList list;
};

// Row-end statistics for Table 4.10: per compact-list row, the number of
// tested pixels before the first hit and after the last hit, each end counted
// on its own (a row with no hit counts once, with all its pixels).
struct RowEndMisses {
  uint64_t count[4] = {0, 0, 0, 0};  // 0, 1, 2, 3+ false pixels
  void add(uint64_t n) { ++count[n < 3 ? n : 3]; }
};

// Builds the compact list (the "list generation" the benchmarks time
// separately) and returns false when the face is too large for B-Convert to
// be sensible (edge lists proportional to a face far larger than the
// viewport): the caller then uses the bounding box.
bool bconvert_list(const ScreenVertex v[3], BConvertVariant variant, const Viewport& vp, BConvertScratch& s);
// Scans the compact list built by bconvert_list.
void bconvert_scan(const ScreenTriangle& t, const Viewport& vp, BConvertScratch& s, FaceSpans& out,
                   ScanCounters& c, RowEndMisses* row_ends);

}  // namespace zs
