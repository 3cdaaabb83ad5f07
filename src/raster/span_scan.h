// Strategy 3 (ours): exact spans. Each edge function, as evaluated in
// floating point, is monotone along a row, so each edge's inside set on a row
// is a half-line: per row and edge, the end is solved for X and then stepped
// to exactly with that edge's own inside test (screen_triangle.h); the span
// is the intersection of the three. The interior is emitted without testing.
// The result is exactly the set the bounding-box scan finds: identical
// fragments, identical images, no missing pixels.
#pragma once

#include "raster/raster_target.h"
#include "raster/screen_triangle.h"

namespace zs {

void scan_span(const ScreenTriangle& t, const Viewport& vp, FaceSpans& out, ScanCounters& c);

}  // namespace zs
