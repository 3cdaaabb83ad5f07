// The scan-convert strategies behind one dispatch: a renderer chooses one by
// name and scans every triangle through a TriangleScanner, never calling a
// strategy directly.
//
// Two steps per triangle, as the seed's benchmark times them apart:
// prepare() is the per-face list generation beyond the triangle's planes
// (B-Convert's edge and compact lists), scan() finds the covered pixels.
#pragma once

#include <cstdint>
#include <string>

#include "raster/bconvert_scan.h"
#include "raster/raster_target.h"
#include "raster/screen_triangle.h"

namespace zs {

enum class ScanStrategy { BBox, BConvert, Span };
const char* to_string(ScanStrategy s);
bool parse_scan_strategy(const std::string& s, ScanStrategy* out);

class TriangleScanner {
 public:
  // `image`: the whole image. B-Convert's size test is against it, not the
  // tile, so B-Convert images do not depend on the tiling.
  TriangleScanner(ScanStrategy strategy, BConvertVariant variant, const Viewport& image)
      : strategy_(strategy), variant_(variant), image_(image) {}

  // Per-face list generation for the triangle scan() will be given; `ok`:
  // whether the triangle set up (a degenerate one is never scanned). A face
  // too large for B-Convert falls back to the bounding box (counted).
  void prepare(const ScreenVertex tri[3], bool ok) {
    use_bconvert_ = ok && strategy_ == ScanStrategy::BConvert;
    if (use_bconvert_ && !bconvert_list(tri, variant_, image_, scratch_)) {
      use_bconvert_ = false;
      ++fallbacks_;
    }
  }
  // The pixels of the prepared triangle `st` inside `vp`, as row runs.
  void scan(const ScreenTriangle& st, const Viewport& vp, FaceSpans& out, ScanCounters& c);

  // Counts since the last take: faces B-Convert left to the bounding box,
  // and B-Convert's row-end statistics (Table 4.10).
  uint64_t take_bconvert_fallbacks() {
    const uint64_t n = fallbacks_;
    fallbacks_ = 0;
    return n;
  }
  RowEndMisses take_row_end_misses() {
    const RowEndMisses r = row_ends_;
    row_ends_ = {};
    return r;
  }

 private:
  ScanStrategy strategy_;
  BConvertVariant variant_;
  Viewport image_;
  bool use_bconvert_ = false;
  uint64_t fallbacks_ = 0;
  RowEndMisses row_ends_;
  BConvertScratch scratch_;
};

}  // namespace zs
