// Strategy 1: the bounding-box scan of the original ZSweep (B-Convert digest §3.3):
// test every pixel centre in the face's screen bounding box with the
// point-in-triangle test, rows outermost as the seed's baseline.
#pragma once

#include "raster/raster_target.h"
#include "raster/screen_triangle.h"

namespace zs {

void scan_bbox(const ScreenTriangle& t, const Viewport& vp, FaceSpans& out, ScanCounters& c);

}  // namespace zs
