// Strategy 3 (ours): exact spans. Per row, the first and last pixel centres
// inside the triangle come from the three edge functions solved for X; only
// the span ends are checked with the exact inside test (screen_triangle.h),
// the interior is emitted without testing. Each edge function, as evaluated
// in floating point, is monotone along a row, so the inside set of a row is
// one interval and the checked ends make it exactly the set the bounding-box
// scan finds: identical fragments, identical images, no missing pixels.
#pragma once

#include "raster/raster_target.h"
#include "raster/screen_triangle.h"

namespace zs {

void scan_span(const ScreenTriangle& t, const Viewport& vp, FaceFragments& out, ScanCounters& c);

}  // namespace zs
