// Z-buffering a tile's triangles on the raster core: each binned triangle is
// set up from its screen corners, scanned by the exact span converter (the
// same pixels the bounding-box scan finds, raster/span_scan.h) and its
// fragments' depths tested against the tile's depth buffer. Nearest wins;
// equal depths go to the smaller id (raster/depth_buffer.h), so the buffer is
// a function of the triangle set, never of bin order, tiles or threads.
// Used by the surface renderer (camera view) and the shadow maps (light view).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raster/depth_buffer.h"
#include "raster/raster_target.h"
#include "raster/screen_triangle.h"

namespace zs {

struct ZBufferCounts {
  uint64_t triangles = 0;     // set up and scanned
  uint64_t degenerate = 0;    // zero screen area (no pixel)
  uint64_t fragments = 0;     // pixel centres covered
  uint64_t depth_writes = 0;  // fragments that became the front sample
  void operator+=(const ZBufferCounts& o) {
    triangles += o.triangles;
    degenerate += o.degenerate;
    fragments += o.fragments;
    depth_writes += o.depth_writes;
  }
};

// Scratch reused across a thread's tiles (no allocation per triangle).
struct ZBufferScratch {
  FaceSpans spans;
  ScanCounters scan;
};

// Depth-tests triangles ids[0..n) (corners index `verts`; depth = the
// vertices' z, perspective-correct when `perspective`) into `db`, which
// covers viewport `vp` (db pixel (x − vp.x0) + (y − vp.y0)·width). The
// sample's id is the triangle's index.
void zbuffer_triangles(const std::vector<ScreenVertex>& verts, const std::vector<std::array<uint32_t, 3>>& corners,
                       const uint32_t* ids, size_t n, bool perspective, const Viewport& vp, DepthBuffer& db,
                       ZBufferScratch& scratch, ZBufferCounts* counts);

// Depth only (shadow maps): keeps each pixel's minimum depth in `depth`
// (viewport-sized, row-major, +inf where empty), with no ids. The minimum of
// a set does not depend on arrival order, and −0 is stored as +0, so the
// buffer is still a function of the triangle set. The same fragments and depth
// expression as zbuffer_triangles; depth_writes is not counted.
void zbuffer_depths(const std::vector<ScreenVertex>& verts, const std::vector<std::array<uint32_t, 3>>& corners,
                    const uint32_t* ids, size_t n, bool perspective, const Viewport& vp, double* depth,
                    ZBufferScratch& scratch, ZBufferCounts* counts);

}  // namespace zs
