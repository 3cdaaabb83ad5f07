#include "raster/triangle_scan.h"

#include "raster/bbox_scan.h"
#include "raster/span_scan.h"

namespace zs {

const char* to_string(ScanStrategy s) {
  switch (s) {
    case ScanStrategy::BBox: return "bbox";
    case ScanStrategy::BConvert: return "bconvert";
    case ScanStrategy::Span: return "span";
  }
  return "?";
}

bool parse_scan_strategy(const std::string& s, ScanStrategy* out) {
  for (ScanStrategy k : {ScanStrategy::BBox, ScanStrategy::BConvert, ScanStrategy::Span})
    if (s == to_string(k)) return *out = k, true;
  return false;
}

void TriangleScanner::scan(const ScreenTriangle& st, const Viewport& vp, FaceSpans& out, ScanCounters& c) {
  if (use_bconvert_) bconvert_scan(st, vp, scratch_, out, c, &row_ends_);
  else if (strategy_ == ScanStrategy::Span) scan_span(st, vp, out, c);
  else scan_bbox(st, vp, out, c);
}

}  // namespace zs
